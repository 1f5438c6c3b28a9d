"""Table 2 of the paper's Example 7.2: sweep µ = k_e and plot σ_ν on Γ3 (saves table2.png)."""
import pathlib
import matplotlib.pyplot as plt
import piezocontact

case = pathlib.Path(__file__).resolve().parents[2] / "cases" / "paper-7.2.toml"
for mu in [0.6, 0.2, 6.8e-2, 5.1e-3]:
    s = piezocontact.solve(case, {"friction.mu": mu, "conductivity.ke": mu})
    plt.plot(s.contact["x"], s.contact["sigma_nu"], label=f"µ = k_e = {mu:g}")
    print(f"µ = k_e = {mu:g}: max |σ_ν| = {s.summary['gamma3']['max_abs_sigma_nu']:.4f} GPa")
plt.xlabel("x on Γ3 [m]"), plt.ylabel("σ_ν [GPa]"), plt.legend(), plt.title("Example 7.2: σ_ν on Γ3")
plt.savefig("table2.png", dpi=120)

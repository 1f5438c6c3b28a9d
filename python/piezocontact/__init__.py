"""piezocontact: static contact of a piezoelectric body with a foundation, P1 finite elements.

    import piezocontact
    solution = piezocontact.solve("cases/paper-7.2.toml", {"friction.mu": 0.2})
    solution.summary["gamma3"]["max_abs_sigma_nu"]
    solution.contact["sigma_nu"]          # one value per Γ3 node (numpy)
    solution.write("out/mu-0.2")          # contact.csv, summary.json, solution.vtu

`solve` runs what `piezocontact run` runs; `overrides` maps dotted case keys to values as
`--set` does (Python or numpy scalars, lists, dicts; a dict sets the keys it names and keeps
the table's others). `Case.from_dict` builds a case from a dict shaped like a case file. Bad
input raises `CaseError`, a `ValueError` whose message is
the command line's (file, line, key and the fix); what `run` warns of a case (a key nothing
reads, a segment end between two nodes) is a `CaseWarning`, a `UserWarning`.
"""

from ._native import Case, CaseError, CaseWarning, Solution, __version__, solve

__all__ = ["Case", "CaseError", "CaseWarning", "Solution", "__version__", "solve"]

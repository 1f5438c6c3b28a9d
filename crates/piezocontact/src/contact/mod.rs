//! Contact on Γ3: the surface and its nodal geometry ([`surface`]), the laws of \[P\] (2.5)–(2.8)
//! each written once ([`law`]), friction on the nodes ([`friction`], [`mollifier`]), the
//! contact model ([`model`]), the multipliers ([`state`]), the foundation ([`foundation`],
//! [`rigid`]) and the loading paths that move it ([`loading`]).
//!
//! Each file imports only its siblings' files, never this one: this file declares and
//! re-exports.

pub mod foundation;
pub mod friction;
pub mod law;
pub mod loading;
pub mod model;
pub mod mollifier;
pub mod rigid;
pub mod state;
pub mod surface;

pub use foundation::Foundation;
pub use friction::NodalFriction;
pub use law::NodeStatus;
pub use loading::{LoadStep, Loading};
pub use model::ContactModel;
pub use mollifier::Mollifier;
pub use state::ContactState;
pub use surface::{ContactSurface, frame};

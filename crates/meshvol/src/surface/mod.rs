//! Adapters that read surfaces, or parts of them, as a [`Surface`](crate::Surface) of their own, without
//! copying faces; and the connected parts of a surface as read.
//!
//! | adapter | what it reads | file |
//! | --- | --- | --- |
//! | [`FaceRange`] | a contiguous run of a surface's faces (one object of a file) | `subsets.rs` |
//! | [`FaceSubset`] | any list of a surface's faces (one part or body) | `subsets.rs` |
//! | [`Oriented`] | a surface with every face reversed, or as it is | `oriented.rs` |
//! | [`Joined`] | several surfaces as one, their faces one after another | `joined.rs` |
//! | [`Moved`] | a surface with every vertex moved by an affine map (a body's pose) | `moved.rs` |
//! | [`connected_parts`] | faces joined at shared vertex positions, before any check | `parts.rs` |
//!
//! Two surfaces built by the check stay in [`crate::topology`], because they read the
//! check's findings: [`crate::topology::SolidView`] (the solid a check found: kept faces
//! turned outward, holes capped) and [`crate::topology::Measured`] (that solid, or the
//! surface as wound).

mod joined;
mod moved;
mod oriented;
mod parts;
mod subsets;

pub use joined::Joined;
pub use moved::Moved;
pub use oriented::Oriented;
pub use parts::connected_parts;
pub use subsets::{FaceRange, FaceSubset};

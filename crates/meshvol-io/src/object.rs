//! [`Object`], a named run of a file's faces: a leaf the readers import.

/// A named part of a file: a contiguous run of the loaded surface's faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Object {
    /// The name the file gives it (an STL solid's name, an OBJ `o`/`g` name, a 3MF
    /// object's name, a glTF node's or mesh's name); possibly empty.
    pub name: String,
    /// Its faces: indices into [`Loaded::surface`](crate::Loaded::surface)'s faces.
    pub faces: std::ops::Range<usize>,
}

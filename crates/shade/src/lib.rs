//! Shading: the mental ray shader model, the built-in shader libraries and BSDFs.
//! Being built; see issue 5.

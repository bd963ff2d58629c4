//! The scene layer: from the `.mi` syntax tree to a renderable world (names resolved,
//! instances flattened, geometry tessellated). Being built; see issue 3.

// Placeholder translation unit for a part of the tree that has no sources yet.

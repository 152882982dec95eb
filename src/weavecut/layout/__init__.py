"""The drawing layer every product uses: the Drawing model, meshes and weaves as Drawings, page
tiling, nesting and cut paths."""

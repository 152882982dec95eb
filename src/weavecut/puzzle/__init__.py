"""The laser-cut jigsaw puzzle (paper section 6): pieces, ring and frame (``pieces``), the frame's
outer outline and size (``frame_size``), paint (``colouring``), cut files (``files``), frame
parts (``frame``), painting guides and colour keys (``guides``), and the workshop folder's
summary and README (``workshop``)."""

"""The laser-cut jigsaw puzzle (paper section 6): pieces, ring, frame, colours, cut files and painting guides."""

"""Paper models (paper section 5.2): strips from a weave, symmetry modules, strip pages and the assembly sheet."""

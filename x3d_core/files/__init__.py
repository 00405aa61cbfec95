"""Files whole: inputs read within bounds, small data documents, atomic writes, and how a path or a
name from a file is shown on a line of output. Imports nothing else of x3d_core."""

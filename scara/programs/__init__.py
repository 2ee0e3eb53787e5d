"""Page programs: the compiled computation of each live panel's move, run by numba in Jupyter and, translated to
JavaScript, in the book's pages (see :class:`scara.plots.panels.PageProgram`)."""

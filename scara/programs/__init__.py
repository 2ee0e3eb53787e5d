"""Page programs: the compiled computation of each live panel's move, run by numba in Jupyter and, translated to
JavaScript, in the book's pages (see :class:`scara.plots.panels.PageProgram`)."""

from .._compile import VECTOR as _VECTOR

#: the numba argument types of a page program, ``program(inputs, data, out)``, and of a data stage,
#: ``prepare(compact, data)`` (None without numba): what the page's translator types them from
PROGRAM_ARGS = None if _VECTOR is None else (_VECTOR, _VECTOR, _VECTOR)
PREPARE_ARGS = None if _VECTOR is None else (_VECTOR, _VECTOR)

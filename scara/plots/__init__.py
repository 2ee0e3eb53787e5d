"""Plotly figure builders for the book: data in, ``go.Figure`` out; no robotics is computed here beyond
calls into the math modules. Importing this package registers the book's offline HTML renderer.

One sub-module per chapter; their public builders are re-exported here.
"""
from ._common import AXIS_COLOURS, JOINT_COLOURS, PALETTE, base_layout, new_figure, slider, use_book_renderer

use_book_renderer()

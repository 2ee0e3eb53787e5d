"""ipywidgets panels for tuning live in Jupyter: the only part of the package that imports ipywidgets.

One sub-module per chapter; their panel builders are re-exported here. Each panel shows the package's error
message in place of the plot when a setting is invalid, never a traceback.
"""

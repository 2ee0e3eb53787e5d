"""Local Sphinx extension: the appendix numbers its equations and figures A.1, A.2, ...

The appendix sits in an unnumbered part of the table of contents, so Sphinx numbers its equations (1), (2)
and its figures Fig. 1, Fig. 2, as if they began the book. Once Sphinx has assigned the numbers, those of the
documents named in ``appendix_letters`` (``{docname: letter}``, set in ``_config.yml``) get the letter in
front: (A.1), Fig. A.2, and every reference to them ({eq}, {numref}) follows.
"""
from __future__ import annotations


def _letter_numbers(app, env):
    for docname, letter in app.config.appendix_letters.items():
        for figtype, numbers in env.toc_fignumbers.get(docname, {}).items():
            for node_id, number in list(numbers.items()):
                if number and number[0] != letter:
                    numbers[node_id] = (letter, *number)
    return []


def setup(app):
    app.add_config_value("appendix_letters", {}, "env", types=[dict])
    app.connect("env-get-updated", _letter_numbers, priority=900)  # after Sphinx numbered the figures
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}

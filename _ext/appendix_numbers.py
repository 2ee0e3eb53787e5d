"""Local Sphinx extension: the appendix numbers its equations and figures A.1, A.2, ...

The appendix sits in an unnumbered part of the table of contents, so Sphinx numbers its equations and figures
as if they began the book, and with one counter per kind for all the unnumbered pages together: the
introduction's figure is Fig. 1, so the appendix's first figure would be Fig. 2. Once Sphinx has assigned the
numbers, those of the documents named in ``appendix_letters`` (``{docname: letter}``, set in ``_config.yml``) are
counted again from 1 in their page's order, each kind on its own, with the letter in front: (A.1), Fig. A.1, and
every reference to them ({eq}, {numref}) follows.
"""
from __future__ import annotations


def _letter_numbers(app, env):
    for docname, letter in app.config.appendix_letters.items():
        for figtype, numbers in env.toc_fignumbers.get(docname, {}).items():
            if all(number and number[0] == letter for number in numbers.values()):
                continue  # lettered already (a rebuild that did not renumber this page)
            ranked = sorted((number, node_id) for node_id, number in numbers.items() if number)
            for rank, (_, node_id) in enumerate(ranked, 1):
                numbers[node_id] = (letter, rank)
    return []


def setup(app):
    app.add_config_value("appendix_letters", {}, "env", types=[dict])
    app.connect("env-get-updated", _letter_numbers, priority=900)  # after Sphinx numbered the figures
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}

"""The book's page panels: the package's kernels translated to JavaScript (:mod:`scara.page.translate`) and
the assets and HTML that run a live panel in a static page with no kernel (:mod:`scara.page.assets`)."""

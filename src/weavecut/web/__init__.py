"""``weave-cut serve``: the web app, a second front end beside ``cli/``.

Its forms are generated from the click commands' own options (``forms``), a request's values
are checked by the click command itself (``queries``), so the messages are the CLI's, and every
kit is made by the CLI's code in a job (``jobs``: the queue, its workers and the result cache).
``server`` is the Starlette app, ``pages`` its HTML, ``uploads`` the drawings people bring,
``static/`` its style sheet, script and pictures (shipped in the package: the app asks no other
host).
"""

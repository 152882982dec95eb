"""The web app (``weave-cut serve``): a second front end beside ``cli/``, over the same
command definitions; its jobs run the commands in child processes (``jobs``)."""

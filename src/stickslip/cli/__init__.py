"""Private: the ``stickslip`` command line (Typer). Its contract is the commands, not this code."""

"""The commands' paths for a machine whose friction has memory (rate-and-state, LuGre):
``stability`` and ``map`` with ``--config``. Each command imports its module when it runs.
"""

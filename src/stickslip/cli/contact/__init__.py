"""The commands' paths for a machine with its contact (``--config`` with a normal DOF or a
Jenkins element): ``simulate``, ``design``, ``map``, ``boundary``, ``cycles``, ``basin`` and
``continue``. Each command imports its module when it runs.
"""

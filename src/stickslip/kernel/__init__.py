"""Private: the numba engine (arrays in, arrays out) behind :func:`stickslip.simulate`.

Nothing here is public API; its names and signatures may change between versions without a
deprecation period. Use :func:`stickslip.simulate` and the sweeps of :mod:`stickslip.sweep`.
"""

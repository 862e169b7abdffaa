"""Analysis: one scene at one pose (``modal``), the eigen solver and its checks (``solve``),
sweeps over poses and the model families."""

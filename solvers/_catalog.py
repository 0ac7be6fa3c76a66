"""Built-in solvers: registry id -> "module:Class" (imported on first use).

Add one line per solver. Order is the order of `harness list solvers`.
"""

BUILTIN: dict[str, str] = {
    # thesis algorithms (written here)
    "sqsd": "solvers.sqsd:SQSD",
    "sd": "solvers.classical:SteepestDescent",
    "fletcher-reeves": "solvers.classical:FletcherReeves",
    "polak-ribiere": "solvers.classical:PolakRibiere",
    "lfopc": "solvers.lfopc:LFOPC",
    "dynamic-q": "solvers.dynamic_q:DynamicQ",
    "dynamic-q-plus": "solvers.dynamic_q_plus:DynamicQPlus",
    "etopc": "solvers.etopc:ETOPC",
    "multistart": "solvers.multistart:Multistart",
    # established solvers (adapters)
    "scipy-cg": "solvers.scipy_adapters:ScipyCG",
    "scipy-bfgs": "solvers.scipy_adapters:ScipyBFGS",
    "scipy-lbfgsb": "solvers.scipy_adapters:ScipyLBFGSB",
    "scipy-slsqp": "solvers.scipy_constrained:ScipySLSQP",
    "scipy-trust-constr": "solvers.scipy_constrained:ScipyTrustConstr",
    "scipy-cobyla": "solvers.scipy_constrained:ScipyCOBYLA",
    "ipopt": "solvers.ipopt:Ipopt",
    "nlopt-mma": "solvers.nlopt_adapters:NloptMMA",
    "nlopt-slsqp": "solvers.nlopt_adapters:NloptSLSQP",
}

"""visco2d's Python tools: run decks, sweep them, read and compare their results, draw them.

One package, one job per module (doc/python.md lists them and what stays hand-written):

  case        read a case folder: summary.txt (typed), history.csv, pressure.csv, results.h5
  runner      find and run the visco2d executable (one process for many decks)
  deck        edit a deck's cards as text (set a value, a word, the integrator)
  hertz       Hertz's impact of a sphere on a rigid plate (the paper's eqs. [43]-[46])
  batch       visco2d-batch: sweeps, threshold searches, the task farm, the results table
  boundary    visco2d-batch boundary: the damage boundary of fruits x surfaces, its chart
  workers     the local workers: one visco2d process each, fed the decks
  diff        visco2d-diff: a run against archived reference outputs
  report      visco2d-report: one picture per case
  figures     the paper's figures; paper_table, study, bench, bench_plastic, bench_sweep, integrators,
              convergence: the benchmark and verification studies; bless, fuzz: the maintainers' tools
"""

__version__ = "1.0"

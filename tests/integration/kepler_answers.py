"""A class's answers to the exercise ``kepler-orbit``, as students type them: right and
wrong, for the grading tests and ``scripts/bench_grade.py``."""

EX = "kepler-orbit"
RIGHT = {"L_star": "sqrt(2*h + 2*m*mu/r)*sqrt(m*(r^2 + r'^2))",
         "r_pp": "(r^2*(2*h*r + m*mu) + r'^2*(4*h*r + 3*m*mu))/(2*r*(h*r + m*mu))",
         "h": "-m*mu*(1 - e^2)/(2*p)"}
WRONG = {"L_star": "-sqrt(2*h + 2*m*mu/r)*sqrt(m*(r^2 + r'^2))",
         "r_pp": "(r^2*(2*h*r + m*mu) + r'^2*(4*h*r + 3*m*mu))/(2*(h*r + m*mu))",
         "h": "-m*mu*Abs(1 - e^2)/(2*p)"}

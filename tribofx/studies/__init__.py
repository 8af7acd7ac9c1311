"""Studies over the cases: wear schemes against Δt, their stability, EHL mesh convergence.

A study drives a case's model; no case imports a study's results.

* :mod:`.wear_dt_study`: the Fig. 4 error of explicit, implicit and BDF2 wear against Δt.
* :mod:`.wear_stability`: the explicit scheme's critical step on the ball on a flat.
* :mod:`.ehl_convergence`: the film's convergence under mesh refinement (cylinder on a layer).
"""

"""The report's sections, one module each, in page order. Each exposes render(report, ctx) -> Section
or None (sections/common.py); adding a section is a module and a line here.
"""
from sections import (animate, changes, cost_model, csg, doom, draw, glossary, kernel, merge, occlude, optimal,
                      scoreboard, segments, theory, verdicts)

SECTIONS = (
    changes.render,     # with --baseline: what changed, before the contents
    scoreboard.render,  # which heuristic for my scene, one picture (before the contents)
    verdicts.render,    # who wins where
    cost_model.render,  # does the cost model predict?
    theory.render,      # does the theory hold? (its findings also head the page)
    optimal.render,     # how far from optimal?
    glossary.render,    # what the metrics mean
    draw.render,        # one section per drawing scene
    merge.render,       # set operations
    csg.render,         # CSG programs beside the peer engines
    animate.render,     # dynamic scenes
    occlude.render,     # occlusion culling
    segments.render,    # 2D segments against the Paterson–Yao bound
    doom.render,        # Doom maps beside the node builders
    kernel.render,      # float against exact geometry
)

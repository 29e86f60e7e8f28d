"""The metrics' meanings, once, grouped as the scene sections' tables are (analysis/metric_docs.json)."""
from sections.common import METRIC_DOCS, Section
from tables import Cell, Column, Table


def render(report, ctx):
    rows = [[d["group"], Cell(k, code=True), d["unit"], d["better"] or "—", d["meaning"]]
            for g in METRIC_DOCS["groups"] for k, d in METRIC_DOCS["metrics"].items() if d["group"] == g]
    t = Table("glossary", "What the metrics mean",
              [Column("group"), Column("metric", left=True), Column("unit"), Column("better"),
               Column("meaning", left=True)], rows)
    return Section([("glossary", "what the metrics mean")],
                   f"<h2 id='glossary'>What the metrics mean</h2>{t.html()}", [t])

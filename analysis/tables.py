"""A table the report shows and exports: one definition, four renderings (HTML, CSV, Markdown, LaTeX).
In the page a table's id is table-NAME, apart from the ids of the headings that link to it.

Cells hold plain values (str, int, float, None) so CSV keeps full precision while the page and the
paper formats round to four significant digits. A cell may also be a Cell, which adds a rendered
text (e.g. "12.5 ± 0.3") and an emphasis flag to its value.
"""
import csv
import html
import io
import re


class Cell:
    def __init__(self, value, text=None, bold=False):
        self.value, self.text, self.bold = value, text, bold


def number(x, digits=4):
    if isinstance(x, bool) or x is None:
        return "" if x is None else ("yes" if x else "no")
    if isinstance(x, int):
        return f"{x:,}".replace(",", " ") if abs(x) >= 10000 else str(x)
    if isinstance(x, float):
        return f"{x:.{digits}g}"
    return str(x)


def text_of(cell):
    if isinstance(cell, Cell):
        return cell.text if cell.text is not None else number(cell.value)
    return number(cell)


def value_of(cell):
    return cell.value if isinstance(cell, Cell) else cell


class Table:
    """name: the export's file stem; columns: (header, unit or "") pairs; command: what remakes it."""

    def __init__(self, name, title, columns, rows, command="", note=""):
        self.name, self.title, self.columns, self.rows = name, title, columns, rows
        self.command, self.note = command, note

    def header_text(self, i):
        head, unit = self.columns[i]
        return f"{head} ({unit})" if unit else head

    def html(self, scroll=False):
        head = "".join(f"<th>{html.escape(self.header_text(i))}</th>" for i in range(len(self.columns)))
        body = []
        for row in self.rows:
            cells = []
            for c in row:
                t = html.escape(text_of(c))
                cells.append(f"<td><b>{t}</b></td>" if isinstance(c, Cell) and c.bold else f"<td>{t}</td>")
            body.append("<tr>" + "".join(cells) + "</tr>")
        table = f"<table id='table-{html.escape(self.name)}'><tr>{head}</tr>{''.join(body)}</table>"
        if scroll:
            table = f"<div class=scroll>{table}</div>"
        note = f"<p class=note>{html.escape(self.note)}</p>" if self.note else ""
        cmd = f"<p class=cmd>Remake: <code>{html.escape(self.command)}</code></p>" if self.command else ""
        return table + note + cmd

    def csv(self):
        out = io.StringIO()
        w = csv.writer(out, lineterminator="\n")
        w.writerow([self.header_text(i) for i in range(len(self.columns))])
        for row in self.rows:
            w.writerow(["" if value_of(c) is None else value_of(c) for c in row])
        return out.getvalue()

    def markdown(self):
        def esc(t):
            return t.replace("|", "\\|")
        lines = [f"**{esc(self.title)}**", "",
                 "| " + " | ".join(esc(self.header_text(i)) for i in range(len(self.columns))) + " |",
                 "|" + "---|" * len(self.columns)]
        for row in self.rows:
            lines.append("| " + " | ".join(
                (f"**{esc(text_of(c))}**" if isinstance(c, Cell) and c.bold else esc(text_of(c))) for c in row) + " |")
        return "\n".join(lines) + "\n"

    def latex(self):
        def esc(t):
            t = re.sub(r"([&%$#_{}])", r"\\\1", t)
            return (t.replace("~", r"\textasciitilde{}").replace("^", r"\textasciicircum{}")
                    .replace("±", r"$\pm$").replace("²", r"$^2$").replace("³", r"$^3$").replace("−", "-")
                    .replace("ρ", r"$\rho$").replace("≤", r"$\le$").replace("≥", r"$\ge$").replace("×", r"$\times$")
                    .replace("Θ", r"$\Theta$").replace("⌈", r"$\lceil$").replace("⌉", r"$\rceil$"))
        spec = "l" + "r" * (len(self.columns) - 1)
        lines = [r"\begin{table}", r"\centering", f"\\caption{{{esc(self.title)}}}",
                 f"\\begin{{tabular}}{{{spec}}}", r"\hline",
                 " & ".join(esc(self.header_text(i)) for i in range(len(self.columns))) + r" \\", r"\hline"]
        for row in self.rows:
            lines.append(" & ".join((f"\\textbf{{{esc(text_of(c))}}}" if isinstance(c, Cell) and c.bold
                                     else esc(text_of(c))) for c in row) + r" \\")
        lines += [r"\hline", r"\end{tabular}", r"\end{table}"]
        return "\n".join(lines) + "\n"

    def render(self, fmt):
        return {"csv": self.csv, "markdown": self.markdown, "latex": self.latex}[fmt]()


EXTENSIONS = {"csv": "csv", "markdown": "md", "latex": "tex"}

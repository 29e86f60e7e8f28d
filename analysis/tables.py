"""A table the report shows and exports: one definition, four renderings (HTML, CSV, Markdown, LaTeX).
Every table of the page is one, so --format exports each. In the page a table's id is table-NAME,
apart from the ids of the headings that link to it.

Cells hold plain values (str, int, float, None) so CSV keeps full precision while the page and the
paper formats round to four significant digits. A cell may also be a Cell, which adds a rendered
text (e.g. "12.5 ± 0.3"), emphasis, a hover title or a span of several columns to its value.
"""
import csv
import html
import io
import re
from collections import namedtuple

# A column: its header, the unit shown after it, a hover title explaining it (the page only) and
# whether its cells are left-aligned text rather than numbers.
Column = namedtuple("Column", "head unit title left", defaults=("", "", False))


class Cell:
    def __init__(self, value, text=None, bold=False, italic=False, code=False, title="", span=1):
        self.value, self.text, self.title, self.span = value, text, title, span
        self.bold, self.italic, self.code = bold, italic, code


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


def span_of(cell):
    return cell.span if isinstance(cell, Cell) else 1


def emphasized(cell, text, marks):
    """text wrapped in the format's marks (code, italic, bold: (open, close) pairs) as the cell asks."""
    if not isinstance(cell, Cell):
        return text
    for on, (start, end) in zip((cell.code, cell.italic, cell.bold), marks):
        if on:
            text = start + text + end
    return text


def content(text):
    """Text for an element's content: quotes need escaping only in attributes."""
    return html.escape(text, quote=False)


HTML_MARKS = (("<code>", "</code>"), ("<i>", "</i>"), ("<b>", "</b>"))
MARKDOWN_MARKS = (("`", "`"), ("*", "*"), ("**", "**"))
LATEX_MARKS = ((r"\texttt{", "}"), (r"\textit{", "}"), (r"\textbf{", "}"))


class Table:
    """name: the export's file stem; columns: Columns or (header, unit) pairs; command: what remakes it.

    groups: a second header row above the columns, as (label, span) pairs covering them in order; a
    None label leaves its columns' headers spanning both rows. The flat formats prefix a grouped
    column's header with its group's label.
    row_heads: each row's first cell names the row (a table of named values): the page shows it as
    a header cell and shows no column headers; the exports keep them.
    """

    def __init__(self, name, title, columns, rows, command="", note="", groups=None, row_heads=False):
        self.name, self.title, self.rows = name, title, rows
        self.columns = [Column(*c) for c in columns]
        self.command, self.note, self.groups, self.row_heads = command, note, groups, row_heads

    def header_text(self, i):
        head, unit = self.columns[i].head, self.columns[i].unit
        return f"{head} ({unit})" if unit else head

    def group_of(self, i):
        """The label of column i's group, None when it has none."""
        start = 0
        for label, span in self.groups or ():
            if start <= i < start + span:
                return label
            start += span
        return None

    def flat_header(self, i):
        group = self.group_of(i)
        return self.header_text(i) if group is None else f"{group}: {self.header_text(i)}"

    def th(self, i, extra=""):
        c = self.columns[i]
        title = f" title='{html.escape(c.title)}'" if c.title else ""
        return f"<th{extra}{title}>{content(self.header_text(i))}</th>"

    def html_head(self):
        if self.row_heads:
            return ""
        if not self.groups:
            return "<tr>" + "".join(self.th(i) for i in range(len(self.columns))) + "</tr>"
        top, bottom, start = [], [], 0
        for label, span in self.groups:
            if label is None:
                top += [self.th(i, " rowspan=2") for i in range(start, start + span)]
            else:
                top.append(f"<th colspan={span}>{content(label)}</th>")
                bottom += [self.th(i) for i in range(start, start + span)]
            start += span
        return f"<tr>{''.join(top)}</tr><tr>{''.join(bottom)}</tr>"

    def html_cell(self, c, column):
        attrs = f" colspan={c.span}" if span_of(c) > 1 else ""
        if isinstance(c, Cell) and c.title:
            attrs += f" title='{html.escape(c.title)}'"
        if self.columns[column].left:
            attrs += " style='text-align:left'"
        tag = "th" if self.row_heads and column == 0 else "td"
        return f"<{tag}{attrs}>{emphasized(c, content(text_of(c)), HTML_MARKS)}</{tag}>"

    def html_row(self, row):
        cells, column = [], 0
        for c in row:
            cells.append(self.html_cell(c, column))
            column += span_of(c)
        return "<tr>" + "".join(cells) + "</tr>"

    def html(self, scroll=False):
        body = "".join(self.html_row(row) for row in self.rows)
        table = f"<table id='table-{html.escape(self.name)}'>{self.html_head()}{body}</table>"
        if scroll:
            table = f"<div class=scroll>{table}</div>"
        note = f"<p class=note>{html.escape(self.note)}</p>" if self.note else ""
        cmd = f"<p class=cmd>Remake: <code>{html.escape(self.command)}</code></p>" if self.command else ""
        return table + note + cmd

    def flat_rows(self, render):
        """Each row as one rendered string per column: a spanning cell, then empty ones it covers."""
        for row in self.rows:
            out = []
            for c in row:
                out += [render(c)] + [""] * (span_of(c) - 1)
            yield out

    def csv(self):
        out = io.StringIO()
        w = csv.writer(out, lineterminator="\n")
        w.writerow([self.flat_header(i) for i in range(len(self.columns))])
        for row in self.flat_rows(lambda c: "" if value_of(c) is None else value_of(c)):
            w.writerow(row)
        return out.getvalue()

    def markdown(self):
        def esc(t):
            return t.replace("|", "\\|")
        lines = [f"**{esc(self.title)}**", "",
                 "| " + " | ".join(esc(self.flat_header(i)) for i in range(len(self.columns))) + " |",
                 "|" + "---|" * len(self.columns)]
        for row in self.flat_rows(lambda c: emphasized(c, esc(text_of(c)), MARKDOWN_MARKS)):
            lines.append("| " + " | ".join(row) + " |")
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
                 " & ".join(esc(self.flat_header(i)) for i in range(len(self.columns))) + r" \\", r"\hline"]
        for row in self.flat_rows(lambda c: emphasized(c, esc(text_of(c)), LATEX_MARKS)):
            lines.append(" & ".join(row) + r" \\")
        lines += [r"\hline", r"\end{tabular}", r"\end{table}"]
        return "\n".join(lines) + "\n"

    def render(self, fmt):
        return {"csv": self.csv, "markdown": self.markdown, "latex": self.latex}[fmt]()


EXTENSIONS = {"csv": "csv", "markdown": "md", "latex": "tex"}

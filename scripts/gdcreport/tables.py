"""Markdown tables as the reports write them: a header row, a |---| rule, one line per row."""


def table_lines(header, rows):
    """The table's lines: cells are written with str(); every row should have len(header) cells."""
    lines = ["| " + " | ".join(str(cell) for cell in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return lines


def table(header, rows):
    """The table as one string (no newline at its end)."""
    return "\n".join(table_lines(header, rows))


def parse_table(lines):
    """The rows (lists of stripped cell texts) of the first Markdown table in lines, the header
    first and the |---| rule left out; a reader's view of what table_lines wrote."""
    rows = []
    for line in lines:
        if line.startswith("|"):
            rows.append([cell.strip() for cell in line.strip().strip("|").split("|")])
        elif rows:
            break  # the table ended
    return rows[:1] + rows[2:]

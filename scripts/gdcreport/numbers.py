"""Numbers as the reports write them: a dash for a missing value, a few significant digits, and
units chosen by magnitude. Pure functions of their arguments."""
import math

MISSING = "–"  # what a table shows for a value that was not measured (None or NaN)


def number(text):
    """A CSV cell as a float; NaN for an empty or unreadable cell (a measure not taken)."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def is_missing(value):
    return value is None or (isinstance(value, float) and math.isnan(value))


def fmt(value, digits=3, whole_from=None):
    """`digits` significant digits; exact zero as "0"; from `whole_from` up (when given) as a whole
    number instead of the exponent form .3g would give 1234 (1.23e+03)."""
    if is_missing(value):
        return MISSING
    if value == 0:
        return "0"
    if whole_from is not None and abs(value) >= whole_from:
        return f"{value:.0f}"
    return f"{value:.{digits}g}"


def _by_magnitude(value, steps):
    """value written by the first (from, divisor, format) of steps whose `from` it reaches."""
    for start, divisor, form in steps:
        if value >= start:
            return form.format(value / divisor)
    start, divisor, form = steps[-1]
    return form.format(value / divisor)


_NS_STEPS = [(1e6, 1e6, "{:.2f} ms"), (1e4, 1e3, "{:.0f} µs"), (1e3, 1e3, "{:.2f} µs"), (-math.inf, 1.0, "{:.0f} ns")]
_MS_STEPS = [(100, 1.0, "{:.0f}"), (10, 1.0, "{:.1f}"), (1, 1.0, "{:.2f}"), (-math.inf, 1.0, "{:.3f}")]


def fmt_ns(ns):
    """A duration given in ns, in ns, µs or ms: three significant digits or a whole number."""
    return MISSING if is_missing(ns) else _by_magnitude(ns, _NS_STEPS)


def fmt_ms(ms):
    """A duration given in ms (number or text), with decimals by magnitude: 123, 12.3, 1.23, 0.123."""
    return _by_magnitude(float(ms), _MS_STEPS)


def fmt_instructions(count):
    """An instruction count: whole below a thousand, else thousands with one decimal ("12.3 k")."""
    if is_missing(count):
        return MISSING
    return f"{count / 1e3:.1f} k" if count >= 1e3 else f"{count:.0f}"


def fmt_count(mean):
    """A mean count (contacts per call): whole when it is, else two decimals."""
    if is_missing(mean):
        return MISSING
    return f"{mean:.0f}" if abs(mean - round(mean)) < 1e-3 else f"{mean:.2f}"


def fmt_percent(fraction):
    """A fraction as a whole per cent with a space before the sign ("12 %")."""
    return f"{100 * fraction:.0f} %"


def ratio(numerator, denominator):
    """numerator ÷ denominator; infinite when only the denominator is 0, NaN when both are."""
    if denominator <= 0:
        return math.inf if numerator > 0 else math.nan
    return numerator / denominator

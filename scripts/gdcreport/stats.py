"""The statistics the reports use, in one place: medians, the Wilson interval of a failure
fraction, and the exact two-sided sign test over paired seeds. Pure functions, standard library
only."""
import math


def median(values):
    """The median (the mean of the middle two for an even count); NaN for no values."""
    ordered = sorted(values)
    n = len(ordered)
    if n == 0:
        return math.nan
    return ordered[n // 2] if n % 2 else 0.5 * (ordered[n // 2 - 1] + ordered[n // 2])


def wilson(k, n, z=1.959964):
    """The Wilson score interval (low, high) of k successes in n trials; 95 % for the default z;
    (0, 1) for no trials."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def paired_by_seed(a, b, happened):
    """a, b: seed -> one contender's result. Over the seeds both ran: (the seeds where `happened`
    holds for a's result and not b's, the other way round, the sign test's p of the two)."""
    common = set(a) & set(b)
    only_a = sum(happened(a[s]) and not happened(b[s]) for s in common)
    only_b = sum(happened(b[s]) and not happened(a[s]) for s in common)
    return only_a, only_b, sign_test(only_a, only_b)


def sign_test(a, b):
    """The exact two-sided sign (binomial, p = 1/2; McNemar exact) test's p of a against b
    discordant pairs: seeds where one side fails (or sleeps later) and the other does not. 1 when
    there are none."""
    n = a + b
    if n == 0:
        return 1.0
    k = min(a, b)
    tail = sum(math.comb(n, i) for i in range(k + 1)) / 2 ** n
    return min(1.0, 2 * tail)

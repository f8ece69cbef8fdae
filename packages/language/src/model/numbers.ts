/**
 * The ranges of Cactal's numbers: in the generated C (LP64, docs/language-reference.md §2) an `int` is
 * a C `long` (64 bits) and a `float` a C `double`. A number literal is read from its text (an int
 * exactly, whatever its size: a JavaScript number holds integers exactly only up to 2^53), so that a
 * value that does not fit is said instead of being changed on the way to C (`1e400` was infinite and
 * written `0.0`, `99999999999999999999` was written as is and truncated by gcc).
 */

/** The smallest and largest `int` (C `long`, 64 bits). */
export const INT_MIN = -(2n ** 63n);
export const INT_MAX = 2n ** 63n - 1n;

/** The largest finite `float` (C `double`). */
export const FLOAT_MAX = Number.MAX_VALUE;

/** The range of an int, for messages. */
export const INT_RANGE_TEXT = `an int is a C long, from ${INT_MIN} to ${INT_MAX}`;

/** The exact integer written `text` (`-12`, `007`), or undefined when it is not an integer literal. */
export function exactInteger(text: string): bigint | undefined {
    return /^[-+]?[0-9]+$/.test(text.trim()) ? BigInt(text.trim()) : undefined;
}

/**
 * Why the integer literal `text` is no `int`, or undefined when it is one (`INT_MIN` to `INT_MAX`).
 * The problem is worded to follow "The integer 123 ": "is too large ...".
 */
export function intLiteralProblem(text: string): string | undefined {
    const n = exactInteger(text);
    if (n === undefined) return undefined; // not an integer: the type check says so
    if (n > INT_MAX) return `is too large for an int (${INT_RANGE_TEXT})`;
    if (n < INT_MIN) return `is too small for an int (${INT_RANGE_TEXT})`;
    return undefined;
}

/**
 * Why the number literal `text` (an integer or a real) is no `float` (C double), or undefined when it
 * is one: its value must be finite (at most ±1.7976931348623157e308), and a literal that is not zero
 * must not round to zero (below 5e-324: gcc would write it 0.0, "floating constant truncated to zero").
 */
export function floatLiteralProblem(text: string): string | undefined {
    const value = Number(text.trim());
    if (Number.isNaN(value)) return undefined; // not a number: the type check says so
    if (!Number.isFinite(value)) {
        return `is too ${value > 0 ? 'large' : 'small'} for a float (a float is a C double, from -${FLOAT_MAX} to ${FLOAT_MAX}): it would be infinite`;
    }
    if (value === 0 && /[1-9]/.test(mantissa(text))) {
        return `is too close to 0 for a float (a float is a C double; its smallest value but 0 is ${Number.MIN_VALUE}): it would be 0`;
    }
    return undefined;
}

/** The digits before the exponent of a number literal (`1.5` of `1.5e-400`). */
function mantissa(text: string): string {
    return text.trim().split(/[eE]/)[0] ?? '';
}

/**
 * The largest C `int`: a port index, a data flow's periodicity (`* k`) and an array size are C ints
 * in the generated C and the runtime (`int Port`, `int periodicity`, `unsigned int` loop counters).
 */
export const C_INT_MAX = 2147483647;

/**
 * The longest duration, in nanoseconds: 2^53 - 1 ns (about 104 days). The generated C holds
 * durations as `int64_t` nanoseconds; the tools (timing analysis, generator, simulator, traces) hold
 * them as numbers, exact up to 2^53: a longer one would reach the C changed.
 */
export const DURATION_NS_MAX = Number.MAX_SAFE_INTEGER;

const UNIT_DIGITS: Record<string, number> = { ns: 0, us: 3, ms: 6, s: 9 };

/** The exact nanoseconds of a time literal (`1.5ms` -> 1500000n, rounded to the nanosecond as model/time.ts does), or undefined. */
export function exactNanoseconds(text: string): bigint | undefined {
    const m = /^(-?)([0-9]+)(?:\.([0-9]+))?(ns|us|ms|s)$/.exec(text.trim());
    if (!m) return undefined;
    const digits = UNIT_DIGITS[m[4]!]!;
    const fraction = (m[3] ?? '').padEnd(digits + 1, '0');
    let ns = BigInt(m[2]!) * 10n ** BigInt(digits) + BigInt(fraction.slice(0, digits) || '0');
    if (fraction[digits]! >= '5') ns += 1n;
    return m[1] ? -ns : ns;
}

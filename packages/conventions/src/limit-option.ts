/**
 * `--limit NAME=VALUE`, as `contract serve`, `contract run` and `contract build` take it: the one
 * reading of the option's text. The build service checks the names and values it gets
 * (packages/build-service/src/limits.ts mergeLimits, which quotes the value as written).
 */

/** `processes=512`, `runSeconds=0.5`, `.5`, `5.`: a name and a positive number as written. */
const LIMIT_OPTION = /^([A-Za-z_]\w*)=(\d+(?:\.\d*)?|\.\d+)$/;

/** The limits a command line asks for (null-prototype records: `__proto__=1` is a name like another, refused as unknown). */
export interface LimitOptions {
    limits: Record<string, number>;
    /** Each value as written: quoted in a refusal, a count or size checked exactly. */
    limitTexts: Record<string, string>;
}

export function emptyLimitOptions(): LimitOptions {
    return { limits: Object.create(null) as Record<string, number>, limitTexts: Object.create(null) as Record<string, string> };
}

/**
 * Adds one `--limit` value (`processes=512`) to `into`; returns why it is refused (`--limit needs
 * NAME=VALUE ...`, or a name given twice: which one was meant is not guessed) or undefined.
 */
export function addLimitOption(into: LimitOptions, text: string | undefined): string | undefined {
    const m = LIMIT_OPTION.exec(text ?? '');
    if (!m || Number(m[2]) <= 0) return `--limit needs NAME=VALUE with a positive number (e.g. processes=512, runSeconds=3600), got ${text ?? 'nothing'}`;
    const earlier = into.limitTexts[m[1]!];
    if (earlier !== undefined) return `--limit ${m[1]!} is given twice (${earlier} and ${m[2]!}): give it once`;
    into.limits[m[1]!] = Number(m[2]);
    into.limitTexts[m[1]!] = m[2]!;
    return undefined;
}

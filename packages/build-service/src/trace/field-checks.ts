/**
 * The character checks of a record line's fields (docs/runtime-api.md "Trace records"), on a
 * range of the line so that a reader can check a field without cutting it out first. Shared by
 * the trace reader (parse.ts) and the IDE's Monitor, which reads the time of a line it does not
 * fold without parsing it: both must accept exactly the same lines.
 */

/** True when s[from, to) is `\d{min,max}`. */
export function isDigitsIn(s: string, min: number, max: number, from = 0, to = s.length): boolean {
    const digits = to - from;
    if (digits < min || digits > max) return false;
    for (let i = from; i < to; i++) {
        const c = s.charCodeAt(i);
        if (c < 48 || c > 57) return false;
    }
    return true;
}

/** True when s[from, to) is `[\w.-]{1,64}` (a module name as the runtime writes it). */
export function isModuleNameIn(s: string, from = 0, to = s.length): boolean {
    if (to - from < 1 || to - from > 64) return false;
    for (let i = from; i < to; i++) {
        const c = s.charCodeAt(i);
        const ok = (c >= 48 && c <= 57) || (c >= 65 && c <= 90) || (c >= 97 && c <= 122) || c === 95 /* _ */ || c === 46 /* . */ || c === 45; /* - */
        if (!ok) return false;
    }
    return true;
}

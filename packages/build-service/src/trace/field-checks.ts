/**
 * The character checks of a record line's fields (docs/runtime-api.md "Trace records"), on a
 * range of the line so that a reader can check a field without cutting it out first. Shared by
 * the trace reader (parse.ts) and the IDE's Monitor, which reads the time of a line it does not
 * fold, and the fields of the kinds every periodic cycle writes, without parsing it: both must
 * accept exactly the same lines and read the same detail words.
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

/** True when s[from, to) is `-?\d{1,15}`: a detail value the reader makes a number (one a double holds exactly). */
export function isPlainIntegerIn(s: string, from = 0, to = s.length): boolean {
    return isDigitsIn(s, 1, 15, from < to && s.charCodeAt(from) === 45 /* - */ ? from + 1 : from, to);
}

/**
 * The first space in s[from, to), or `to`. A range that ends before the text does is searched by
 * a loop: indexOf would search on past it (through the rest of a trace event, for every line).
 */
export function spaceIn(s: string, from: number, to: number): number {
    if (to === s.length) {
        const at = s.indexOf(' ', from);
        return at < 0 ? to : at;
    }
    for (let i = from; i < to; i++) if (s.charCodeAt(i) === 32) return i;
    return to;
}

/**
 * Where the value of the first word `key=...` of the detail s[from, to) starts, or -1 (words are
 * separated by spaces). A detail that is the whole text is searched with indexOf, a range of a
 * larger text word by word (see spaceIn).
 */
export function wordValueIn(s: string, key: string, from = 0, to = s.length): number {
    const n = key.length;
    if (from === 0 && to === s.length) {
        for (let at = s.indexOf(key); at >= 0; at = s.indexOf(key, at + 1)) {
            if ((at === 0 || s.charCodeAt(at - 1) === 32) && s.charCodeAt(at + n) === 61 /* = */) return at + n + 1;
        }
        return -1;
    }
    for (let at = from; at < to;) {
        if (at + n < to && s.charCodeAt(at + n) === 61 /* = */ && s.startsWith(key, at)) return at + n + 1;
        at = spaceIn(s, at, to) + 1;
    }
    return -1;
}

/**
 * True when `word` is one of the space-separated words of the detail s[from, to): what a reader
 * tests rather than the detail's first or last word, so that a `key=value` field or a word the
 * runtime adds later, anywhere, does not change what it concludes.
 */
export function hasWordIn(s: string, word: string, from = 0, to = s.length): boolean {
    const n = word.length;
    for (let at = from; at < to;) {
        const end = spaceIn(s, at, to);
        if (end - at === n && s.startsWith(word, at)) return true;
        at = end + 1;
    }
    return false;
}

/**
 * What a crash signal means, in a beginner's words: the one table every place that tells a crash
 * uses (the failed run's message and its Problems entry, `contract run --verbose`'s crash frames,
 * `contract trace`, the IDE's Monitor). The signals are those the runtime's crash handler reports
 * (runtime/src/crash_report.c): SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT.
 */

/** The meaning of each crash signal, by number (Linux) and name. */
export const CRASH_SIGNALS: readonly { signal: number; name: string; meaning: string }[] = [
    { signal: 11, name: 'SIGSEGV', meaning: 'a bad pointer: NULL, freed, or past the end of an array' },
    { signal: 8, name: 'SIGFPE', meaning: 'an integer division by zero, or INT_MIN / -1' },
    { signal: 4, name: 'SIGILL', meaning: 'code gcc knew to be undefined (such as a division by a constant zero), or a trap' },
    { signal: 7, name: 'SIGBUS', meaning: 'a bad memory access: a misaligned pointer, or a mapped file cut short' },
    { signal: 6, name: 'SIGABRT', meaning: 'the code called abort(), or an assert() failed: its message is on stderr' },
];

/** The meaning of crash signal `signal` (its number, or its name `SIGFPE`), undefined for another one. */
export function crashSignalMeaning(signal: number | string): string | undefined {
    return CRASH_SIGNALS.find((s) => s.signal === signal || s.name === signal)?.meaning;
}

/** The first `signal N` in `text` (`died by signal 8 (Floating point exception)`, `signal 8 (SIGFPE)`), with its meaning appended as `: MEANING`; `text` unchanged when it names no crash signal or already tells it. */
export function withCrashMeaning(text: string): string {
    const m = /\bsignal (\d{1,2})\b/.exec(text);
    const meaning = m ? crashSignalMeaning(Number(m[1])) : undefined;
    return meaning && !text.includes(meaning) ? `${text}: ${meaning}` : text;
}

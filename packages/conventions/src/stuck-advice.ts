/**
 * The cause ORD writes at the end of a stuck report (`STUCK: M has not finished release #N after
 * K periods[ (...)]: <cause>`, runtime/src/engines/ord_stuck_cause.c) for a module that runs on:
 * the question about its exec region, or what ORD saw of the module's thread (running, waiting,
 * starved, blocked writing its output to a full pipe or printing without end, stopped). The CLI and the trace story replace it when they know better (the module
 * had crashed or exited), so every form is matched here, once.
 */
export const STUCK_ADVICE = new RegExp(
    ': (?:' +
        [
            'does its exec region set \\*stateindex = -1\\?',
            'does its exec region loop, or never set \\*stateindex = -1\\? \\(its thread got \\d+% of a CPU in the last \\d+(?:\\.\\d+)? s, more than a period needs; a loaded machine gives it less\\)',
            // a log of a runtime before that wording
            'does its exec region loop, or never set \\*stateindex = -1\\? \\(it ran \\d+% of the last \\d+(?:\\.\\d+)? s\\)',
            "it is blocked writing its output: the pipe is full \\(it prints faster than the run's output is read\\): does its exec region print too much\\?",
            'it prints without end \\(\\d+(?:\\.\\d+)? MiB written in the last \\d+(?:\\.\\d+)? s\\): does its exec region print too much, or loop printing\\?',
            'it is waiting, not running \\(a sleep, a read, a lock or a send to a full mailbox in its exec region\\?\\)',
            'it wanted the CPU but got only \\d+% of it in the last \\d+(?:\\.\\d+)? s: do processes at real-time priority or an overloaded machine starve it, or does its exec region loop\\?',
            'it is stopped \\(by SIGSTOP, or a debugger holds it\\)',
        ].join('|') +
        ')',
);

/** `message` without ORD's cause for a module that runs on (STUCK_ADVICE), when it ends with one. */
export function withoutStuckAdvice(message: string): string {
    const m = STUCK_ADVICE.exec(message);
    return m && m.index + m[0].length === message.length ? message.slice(0, m.index) : message;
}

import { describe, expect, it } from 'vitest';
import { STUCK_ADVICE, withoutStuckAdvice } from './stuck-advice.js';

// each cause ord_stuck_cause.c writes (runtime/tests/engines/test_ord.c checks the C side's words)
const CAUSES = [
    'does its exec region set *stateindex = -1?',
    'does its exec region loop, or never set *stateindex = -1? (its thread got 8% of a CPU in the last 0.5 s, more than a period needs; a loaded machine gives it less)',
    'does its exec region loop, or never set *stateindex = -1? (it ran 97% of the last 1.0 s)',
    "it is blocked writing its output: the pipe is full (it prints faster than the run's output is read): does its exec region print too much?",
    'it prints without end (12.0 MiB written in the last 0.5 s): does its exec region print too much, or loop printing?',
    'it is waiting, not running (a sleep, a read, a lock or a send to a full mailbox in its exec region?)',
    'it wanted the CPU but got only 3% of it in the last 5.0 s: do processes at real-time priority or an overloaded machine starve it, or does its exec region loop?',
    'it is stopped (by SIGSTOP, or a debugger holds it)',
];

describe('ORD stuck causes', () => {
    it('matches every cause of a module that runs on, and strips it from the end of a sentence', () => {
        for (const cause of CAUSES) {
            const sentence = `CTL has not finished release #2 after 100 periods (its schema's new cycle waits for it): ${cause}`;
            expect(STUCK_ADVICE.test(sentence)).toBe(true);
            expect(withoutStuckAdvice(sentence)).toBe("CTL has not finished release #2 after 100 periods (its schema's new cycle waits for it)");
        }
    });

    it('leaves a module no longer running, and a cause not at the end, alone', () => {
        const gone = 'CTL has not finished release #2 after 10 periods: it is no longer running (it crashed or was killed)';
        expect(STUCK_ADVICE.test(gone)).toBe(false);
        expect(withoutStuckAdvice(gone)).toBe(gone);
        const traced = `stuck: CTL has not finished release #2 after 10 periods: ${CAUSES[1]} (goTo)`;
        expect(withoutStuckAdvice(traced)).toBe(traced);
    });
});

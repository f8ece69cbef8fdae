/**
 * docs/language-reference.md §6, supervisor-subscribe-conflict: each subscribe to an input port is
 * warned once, against the first earlier subscribe to that port whose rule may be active with its
 * own (rules never active at once left out). A supervisor with several conflicts: which subscribes
 * are warned, in which order, against which, with which message and range. Pinned as the check
 * gave them before it looked the first one up in an index (model/first-overlapping.ts).
 */
import { describe, expect, it } from 'vitest';
import { architecture, supervisor } from './architecture-fixture.js';
import { build } from './helpers.js';

const POST = '[elapsed=50ms]';
/** Subscribes to :1 (MAA:0), :2 (MAA:2, MAB:1) and :3 (MSC:1) in rules of every kind of relation. */
const RULES = [
    // :2 — A first; B only after A's end (A active once): apart; C at 3 ms: the same producer as A
    `A: [elapsed=1ms] subscribe MAA:2 =* :2 ${POST}`,
    `B: [endof(A)] subscribe MAB:1 =* :2 [MAB:1]`,
    `C: [elapsed=3ms] subscribe MAA:2 =* :2 ${POST}`,
    // another producer after C's end, but A may still be active; :3's first subscribe
    `D: [endof(C)] subscribe MAB:1 =* :2; subscribe MSC:1 => :3 ${POST}`,
    // :1 — a chain H0 -> H1 -> H2, and K beside H2 on H1's end: apart from H0 and H1, not from H2
    `H0: [elapsed=1ms] subscribe MAA:0 =* :1 ${POST}`,
    `H1: [endof(H0)] subscribe MAA:0 =* :1 ${POST}`,
    `H2: [endof(H1)] subscribe MAA:0 =* :1 ${POST}`,
    `K: [endof(H1)] subscribe MAA:0 =* :1 ${POST}`,
    // one rule subscribing :3 twice
    `G: [elapsed=6ms] subscribe MSC:1 => :3; subscribe MSC:1 => :3 ${POST}`,
    // a turn that may hold two (P from 1 ms, Q from 2 ms): Q warned against P, saying why
    `P: [elapsed=1ms or endof(Q)] subscribe MAB:1 =* :2 ${POST}`,
    `Q: [elapsed=2ms or endof(P)] subscribe MAB:1 =* :2 ${POST}`,
    // a turn started once: T and U never active together, but both may be with A
    `T: [elapsed=7ms or endof(U)] subscribe MAA:0 =* :1 ${POST}`,
    `U: [endof(T)] subscribe MAA:0 =* :1 ${POST}`,
].join('\n');
/** A second function, which may run at the same time as `action`. */
const OTHER = `other() { rules { O: [elapsed=1ms] subscribe MAA:0 =* :1; subscribe MSC:1 => :3 ${POST} } }`;

describe('supervisor-subscribe-conflict on a supervisor with several conflicts', () => {
    it('warns each subscribe once, against the first earlier one its rule may be active with, in written order', async () => {
        const built = await build(architecture({ 'sup.contract': supervisor(RULES, { more: OTHER }) }));
        const found = (built.docs.get('sup.contract')!.diagnostics ?? [])
            .filter((d) => String(d.code ?? (d.data as { code?: string } | undefined)?.code) === 'supervisor-subscribe-conflict')
            .map((d) => `${d.range.start.line + 1}:${d.range.start.character + 1}-${d.range.end.line + 1}:${d.range.end.character + 1} ${d.message}`);
        expect(found).toEqual([
            "20:38-20:39 Input event port :2 (connection_status) is also subscribed to MAA:2 by rule A: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :2 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "21:35-21:36 Input event port :2 (connection_status) is also subscribed to MAA:2 (rule A): an input port has at most one producer at a time. Make sure these rules are never active at once, or use another input port for MAB:1.",
            "25:36-25:37 Input event port :1 (message_received) is also subscribed to MAA:0 by rule H2: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :1 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events. They may be active at once: K and H2 take turns on the endof of another rule, but endof(H1) starts 2 of them (H2, K).",
            "26:38-26:39 Input event port :3 (failure) is also subscribed to MSC:1 by rule D: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :3 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "26:61-26:62 Input event port :3 (failure) is also subscribed to MSC:1 by rule D: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :3 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "27:50-27:51 Input event port :2 (connection_status) is also subscribed to MAA:2 (rule A): an input port has at most one producer at a time. Make sure these rules are never active at once, or use another input port for MAB:1.",
            "28:50-28:51 Input event port :2 (connection_status) is also subscribed to MAA:2 (rule A): an input port has at most one producer at a time. Make sure these rules are never active at once, or use another input port for MAB:1.",
            "29:50-29:51 Input event port :1 (message_received) is also subscribed to MAA:0 by rule H0: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :1 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "30:35-30:36 Input event port :1 (message_received) is also subscribed to MAA:0 by rule H0: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :1 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "33:60-33:61 Input event port :1 (message_received) is also subscribed to MAA:0 by rule H0: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :1 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.",
            "33:83-33:84 Input event port :3 (failure) is also subscribed to MSC:1 by rule D: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: `port :3 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events."
        ]);
    });
});

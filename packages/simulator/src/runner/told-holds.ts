/**
 * The verbose report's holds: a supervisor's `module_hold` and `flow_hold` records (sim_world.c
 * writes them as a run's engines do) told as `contract trace` tells them, `module M: hold taken
 * (it was running)`, `event flow A:0 -> B:0: hold dropped (kept connected: …)`, unless the record
 * only confirms the action line just before it (`start module M` then `hold taken (started it)`,
 * `connect A:0 =* B:0` then `hold taken`): the story's rule (confirmingHold).
 */
import { confirmingHold, holdText, type KnownRecord } from '@contract-studio/build-service/trace';
import type { ActionRecord, SimTraceRecord } from './protocol.js';
import { actionAsLogged, engineLine } from '../trace/steps-to-trace.js';

const isHold = (kind: string): kind is 'module_hold' | 'flow_hold' => kind === 'module_hold' || kind === 'flow_hold';

/** The hold record an action line makes its supervisor's next hold record confirm (`kind|peer|detail`). */
function expected(a: ActionRecord): string | undefined {
    const rec = engineLine(a.timeNs, a.who, 'supervisor', actionAsLogged(a.what));
    const hold = rec.kind === 'supervisor' ? confirmingHold((rec as KnownRecord).fields) : undefined;
    return hold && `${hold.kind}|${hold.peer}|${hold.detail}`;
}

/** The hold records of one step worth a line (`module M: detail`), at their times, in the harness's order. */
export function toldHolds(actions: readonly ActionRecord[], records: readonly SimTraceRecord[]): Array<{ t: number; seq: number; who: string; text: string }> {
    const items = [
        ...actions.filter((a) => a.who !== 'ORD').map((a, i) => ({ t: a.timeNs, seq: a.seq ?? -1, i, who: a.who, action: a })),
        ...records.filter((r) => isHold(r.kind)).map((r, i) => ({ t: r.timeNs, seq: r.seq ?? -1, i: actions.length + i, who: r.module, hold: r })),
    ].sort((a, b) => a.t - b.t || a.seq - b.seq || a.i - b.i);
    const awaited = new Map<string, string>();
    const out: Array<{ t: number; seq: number; who: string; text: string }> = [];
    for (const x of items) {
        if ('action' in x) {
            const e = expected(x.action);
            if (e) awaited.set(x.who, e);
            else awaited.delete(x.who);
            continue;
        }
        const r = x.hold;
        const confirms = awaited.get(x.who) === `${r.kind}|${r.peer}|${r.detail}`;
        awaited.delete(x.who);
        if (!confirms && isHold(r.kind)) out.push({ t: x.t, seq: x.seq, who: x.who, text: holdText(r.kind, r.peer, r.detail) });
    }
    return out;
}

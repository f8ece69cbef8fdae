/**
 * A simulation step's actions as a run's log words them, for the verbose report (`contract
 * simulate --verbose`) and the IDE's Simulate panel: every supervisor undo prefixed `undo: `
 * (actionAsLogged), ORD's lines as they are, and a supervisor's `module_hold` / `flow_hold`
 * records (sim_world.c writes them as a run's engines do) told as `contract trace` tells them,
 * `module M: hold taken (it was running)`, `event flow A:0 -> B:0: hold dropped (kept connected:
 * …)`, unless the record only confirms the action line just before it (`start module M` then
 * `hold taken (started it)`, `connect A:0 =* B:0` then `hold taken`): the story's rule
 * (confirmingHold). Browser-safe.
 */
import { confirmingHold, holdText, type KnownRecord } from '@contract-studio/build-service/trace';
import type { ActionRecord, SimTraceRecord } from '../runner/protocol.js';
import { actionAsLogged, engineLine } from './steps-to-trace.js';

/** One line: at its virtual time, in the harness's order (seq, -1 when unknown). */
export interface ActionLine {
    t: number;
    seq: number;
    who: string;
    text: string;
}

const isHold = (kind: string): kind is 'module_hold' | 'flow_hold' => kind === 'module_hold' || kind === 'flow_hold';

/** The hold record an action line makes its supervisor's next hold record confirm (`kind|peer|detail`). */
function expected(a: ActionRecord): string | undefined {
    const rec = engineLine(a.timeNs, a.who, 'supervisor', actionAsLogged(a.what));
    const hold = rec.kind === 'supervisor' ? confirmingHold((rec as KnownRecord).fields) : undefined;
    return hold && `${hold.kind}|${hold.peer}|${hold.detail}`;
}

/** The step's action lines and the hold lines worth telling, in time order, then the harness's. */
export function actionLines(actions: readonly ActionRecord[], records: readonly SimTraceRecord[] = []): ActionLine[] {
    const items = [
        ...actions.map((a, i) => ({ t: a.timeNs, seq: a.seq ?? -1, i, who: a.who, action: a })),
        ...records.filter((r) => isHold(r.kind)).map((r, i) => ({ t: r.timeNs, seq: r.seq ?? -1, i: actions.length + i, who: r.module, hold: r })),
    ].sort((a, b) => a.t - b.t || a.seq - b.seq || a.i - b.i);
    const awaited = new Map<string, string>();
    const out: ActionLine[] = [];
    for (const x of items) {
        if ('action' in x) {
            const a = x.action;
            out.push({ t: x.t, seq: x.seq, who: a.who, text: a.who === 'ORD' ? a.what : actionAsLogged(a.what) });
            if (a.who === 'ORD') continue;
            const e = expected(a);
            if (e) awaited.set(a.who, e);
            else awaited.delete(a.who);
            continue;
        }
        const r = x.hold;
        const confirms = awaited.get(x.who) === `${r.kind}|${r.peer}|${r.detail}`;
        awaited.delete(x.who);
        if (!confirms && isHold(r.kind)) out.push({ t: x.t, seq: x.seq, who: x.who, text: holdText(r.kind, r.peer, r.detail) });
    }
    return out;
}

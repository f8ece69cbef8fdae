/**
 * A readable story of a recorded run from its trace records (`contract trace`): supervisor
 * decisions with their causes, functions started/stopped/refused, schema activations,
 * conflicts, deadline misses with their cycle, overruns, module starts and exits. Releases,
 * completions and deliveries are counted, not told one by one. Pure: returns the lines.
 */
import { isRule, type KnownRecord, type RuleCause, type TraceRecord, type TraceRecordBase } from './records.js';

function describeCause(c: RuleCause): string {
    switch (c.kind) {
        case 'event': return `${c.module}:${c.port} = ${c.value}`;
        case 'started': return `started(${c.rule})`;
        case 'endof': return `endof(${c.rule})`;
        case 'duration': return `duration(${c.rule})=${ms(c.ns)}`;
        case 'elapsed': return `elapsed=${ms(c.ns)}`;
        case 'stop': return 'its function stopped';
        case 'other': return c.text;
    }
}

function ms(ns: number): string {
    return `${Number((ns / 1e6).toFixed(3))}ms`;
}

/* the readable lines told (by their `what`, text-lines.ts); deadline misses come from their typed record */
const SUPERVISOR_TOLD = new Set(['function_started', 'function_stopped', 'function_refused', 'refused']);
const SCHEDULER_TOLD = new Set(['activate', 'deactivate', 'conflict', 'refused', 'overrun', 'missed_tick', 'gave_up']);

/** One line per told record, `+S.mmmmmm MODULE what`, then a summary line of counts. */
export function renderStory(records: TraceRecord[]): string[] {
    const timed = records.filter((r): r is KnownRecord => r.kind !== 'unknown');
    const t0 = timed.length ? BigInt(timed[0]!.monoNs) : 0n;
    const at = (r: TraceRecordBase) => `+${(Number(BigInt(r.monoNs) - t0) / 1e9).toFixed(6)}s ${r.module.padEnd(4)}`;
    const lines: string[] = [];
    const counts = new Map<string, number>();
    for (const r of records) {
        counts.set(r.kind, (counts.get(r.kind) ?? 0) + 1);
        if (r.kind === 'unknown') continue;
        if (isRule(r)) {
            lines.push(`${at(r)} rule ${r.function}.${r.rule} ${r.active ? 'active  ' : 'inactive'} <- ${describeCause(r.causeEvent)}`);
            continue;
        }
        const k = r as KnownRecord;
        const what = String(k.fields['what'] ?? '');
        if (k.kind === 'supervisor' && SUPERVISOR_TOLD.has(what)) lines.push(`${at(k)} ${k.detail}`);
        else if (k.kind === 'scheduler' && SCHEDULER_TOLD.has(what)) lines.push(`${at(k)} ${k.detail}`);
        else if (k.kind === 'ord_deadline_miss') lines.push(`${at(k)} deadline miss (ORD:0): ${k.fields['schema']} cycle ${k.fields['cycle']}`);
        else if (k.kind === 'module_started') lines.push(`${at(k)} started (${k.detail})`);
        else if (k.kind === 'module_exit') lines.push(`${at(k)} exited (${k.detail})`);
        else if (k.kind === 'error') lines.push(`${at(k)} error: ${k.detail}`);
    }
    const n = (kind: string) => counts.get(kind) ?? 0;
    lines.push(`${records.length} records: ${n('ord_release')} releases, ${n('ord_complete')} completed cycles, ${n('ord_deadline_miss')} deadline misses, ` +
        `${n('sup_rule')} rule changes, ${n('data_received')} data and ${n('event_received')} event deliveries, ${n('unknown')} unreadable line(s)`);
    return lines;
}

/**
 * A supervisor's action lines whose outcome has a record of its own (text-lines.ts: field `action`):
 * `start module M (priority P)` and `undo: stop module M` (module_hold), `connect A:p =* B:i` and
 * `undo: disconnect A:p =* B:i` (flow_hold), `set priority of M to P (claim #N)` and `undo: release
 * priority claim #N on M` (module_priority, when the module answers). sup_main.c writes the hold
 * record right after the line; when it says only that the action was done, it is the record
 * confirmingHold names: `contract trace` does not tell it again, the simulator's trace writes it
 * after the line as a run does (steps-to-trace.ts). Browser-safe.
 */

/** The hold record that only says an action line was done: its kind, peer and detail. */
export interface ConfirmingHold {
    kind: 'module_hold' | 'flow_hold';
    peer: string;
    detail: string;
}

/**
 * The name of an event flow's holds (a flow_hold record's peer), as value_ops.c engine_flow_hold_name
 * makes it: `flow-SRC-p-DST-i`, or, when that is 64 characters or more (CONTRACT_NAME_MAX), `flow-`
 * and the 16 hex digits of its 64-bit FNV-1a hash.
 */
export function flowHoldName(src: string, srcPort: number | string, dst: string, dstPort: number | string): string {
    const full = `flow-${src}-${srcPort}-${dst}-${dstPort}`;
    const bytes = new TextEncoder().encode(full);
    if (bytes.length < 64) return full;
    return `flow-${fnv1a64(bytes)}`;
}

/**
 * 64-bit FNV-1a of `bytes` (with the runtime's offset basis) as 16 hex digits, in four 16-bit lanes (every product stays below 2^53):
 * h * 0x100000001b3 = h * 0x1b3 + (h << 40), and 40 bits is two lanes and 8 bits. A forged log line
 * names a flow of up to 4 KB: BigInt arithmetic took ten times as long as reading the line.
 */
function fnv1a64(bytes: Uint8Array): string {
    // engine_flow_hold_name's offset basis (value_ops.c), 1469598103934665603 = 0x14650fb0739d0383 (not FNV's usual
    // 0xcbf29ce484222325: the names are the runtime's, so its basis), low lane first
    let h0 = 0x0383, h1 = 0x739d, h2 = 0x0fb0, h3 = 0x1465;
    for (const b of bytes) {
        h0 ^= b;
        const t0 = h0 * 0x1b3;
        let t1 = h1 * 0x1b3;
        let t2 = h2 * 0x1b3 + (h0 << 8);
        const t3 = h3 * 0x1b3 + (h1 << 8);
        t1 += t0 >>> 16;
        h0 = t0 & 0xffff;
        t2 += t1 >>> 16;
        h1 = t1 & 0xffff;
        h3 = (t3 + (t2 >>> 16)) & 0xffff;
        h2 = t2 & 0xffff;
    }
    const hex = (x: number) => x.toString(16).padStart(4, '0');
    return hex(h3) + hex(h2) + hex(h1) + hex(h0);
}

/**
 * The hold record that would only confirm the action line of these fields (a `supervisor`
 * record's, text-lines.ts), or undefined (another line, or a priority claim: its module_priority
 * record says the priority the module had).
 */
export function confirmingHold(fields: Readonly<Record<string, string | number>>): ConfirmingHold | undefined {
    const module = String(fields['module'] ?? '');
    switch (fields['action']) {
        case 'start_module': return { kind: 'module_hold', peer: module, detail: 'hold taken (started it)' };
        case 'stop_module': return { kind: 'module_hold', peer: module, detail: 'last hold dropped (stopped)' };
        case 'connect':
        case 'disconnect': {
            const peer = flowHoldName(module, fields['port'] ?? '', String(fields['to_module'] ?? ''), fields['to_port'] ?? '');
            return { kind: 'flow_hold', peer, detail: fields['action'] === 'connect' ? 'hold taken' : 'last hold dropped (disconnected)' };
        }
        default: return undefined;
    }
}

/**
 * The supervisors' undos of periodic schemas sent to ORD, followed until ORD serves them, and what
 * its end left unserved: one reader for `contract trace` (story.ts) and the IDE's Monitor, so both
 * say it in the same words.
 *
 * ORD serves an undo with its `deactivate S (activation #N from SUP)` or `ignored: deactivate S`;
 * one the supervisor could not send is followed by its own `error` record (told as such, not
 * here). An undo still unserved when ORD's exit or crash record is read reached ORD's mailbox after
 * ORD's last read of it (ORD was stopped or crashed first): told with that record (atOrdEnd). One
 * still unserved when the records end, ORD's log having no exit record (ORD killed by SIGKILL or
 * terminated at the stop: it writes none), is told only once the run is seen to have ended for it —
 * the exit or crash record of the supervisor that sent it read after it (at a run's end the
 * launcher stops the supervisors first: their undos are their last acts) — never while an undo may
 * just be in flight (atRecordsEnd).
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** Undos followed at most (a run has far fewer; a forged log's are left out). */
const UNDOS_FOLLOWED = 4096;

/** What an end of ORD left unserved: the schemas that stayed active, and the sentence that says it. */
export interface UnservedUndos {
    schemas: string[];
    text: string;
    /** mono_ns of the last of those undos. */
    monoNs: string;
}

interface Undo {
    /** `SUP's undo: deactivate schema S (activation #N)` */
    words: string;
    schema: string;
    monoNs: string;
    /** The supervisor that sent it: its exit or crash record was read after it (the run stopped, the undo was its last act). */
    senderEnded?: boolean;
    sender: string;
}

export class UndosToOrd {
    /** `SUP\0schema\0activation` -> the undo. */
    private readonly unserved = new Map<string, Undo>();
    /** The key of each supervisor's last undo to ORD (a failed send's record follows it). */
    private readonly lastUndoOf = new Map<string, string>();
    /** A launcher's KILL was read: the run is stopping. */
    private runStopping = false;
    /** ORD's exit or crash record was read (its end told what it left). */
    private ordEnded = false;

    /** Follows one record (any kind, in time order). */
    see(k: KnownRecord): void {
        const what = String(k.fields['what'] ?? '');
        if (k.kind === 'request_received' && k.peer === 'contract-launch' && k.detail.startsWith('KILL')) this.runStopping = true;
        if (k.kind === 'module_exit' || k.kind === 'module_crashed') {
            if (k.module === 'ORD') this.ordEnded = true;
            else for (const u of this.unserved.values()) if (u.sender === k.module) u.senderEnded = true;
        }
        if (k.kind === 'module_started' && k.module === 'ORD') this.ordEnded = false;
        if (k.kind === 'supervisor' && what === 'action' && k.peer === 'ORD' && k.detail.startsWith('undo: deactivate schema ') && k.fields['activation'] !== undefined) {
            const schema = String(k.fields['schema']);
            const key = `${k.module}\0${schema}\0${String(k.fields['activation'])}`;
            if (!this.unserved.has(key) && this.unserved.size >= UNDOS_FOLLOWED) return;
            this.unserved.set(ownString(key), { words: ownString(`${k.module}'s ${k.detail.replace(/, to ORD\)$/, ')')}`), schema: ownString(schema), monoNs: ownString(k.monoNs), sender: ownString(k.module) });
            this.lastUndoOf.set(ownString(k.module), ownString(key));
            return;
        }
        // the undo was not sent (ORD had ended, the send failed): its own record tells it
        const last = this.lastUndoOf.get(k.module);
        if (last && ((k.kind === 'error' && k.detail.startsWith('STOP request to ORD:')) || (k.kind === 'supervisor' && what === 'error' && k.peer === 'ORD'))) {
            this.unserved.delete(last);
            this.lastUndoOf.delete(k.module);
            return;
        }
        if (k.kind === 'supervisor' && k.module !== 'ORD') this.lastUndoOf.delete(k.module); // its next record: the undo was sent
        if (k.kind !== 'scheduler' || k.module !== 'ORD') return;
        if (what === 'deactivate') this.unserved.delete(`${String(k.fields['requester'])}\0${String(k.fields['schema'])}\0${String(k.fields['activation'])}`);
        if (what === 'ignored' && k.fields['schema'] !== undefined) {
            const schema = `\0${String(k.fields['schema'])}\0`;
            const served = [...this.unserved.keys()].find((key) => key.includes(schema));
            if (served) this.unserved.delete(served);
        }
    }

    /**
     * At ORD's exit or crash record (after see()): what it left unserved, `while the run stopped: ORD
     * ended before it served SUP's undo: deactivate schema S (activation #N): S stayed active to its
     * end (...)` (without `while the run stopped: ` when no launcher's KILL was read); undefined when
     * none is left.
     */
    atOrdEnd(): UnservedUndos | undefined {
        const left = this.take();
        if (!left) return undefined;
        return {
            schemas: left.schemas,
            monoNs: left.monoNs,
            text: `${this.runStopping ? 'while the run stopped: ' : ''}ORD ended before it served ${left.words}: ` +
                `${left.schemas.join(', ')} stayed active to its end (the undo reached ORD's mailbox after ORD's last read of it)`,
        };
    }

    /**
     * At the end of the records (a recorded run's logs all read, a live run's job ended): the undos
     * ORD's log never answered when that log has no exit record (ORD was killed, or terminated at
     * the stop: neither writes one), `ORD's log ends with no exit record (it was killed or
     * terminated: ...) and no answer to SUP's undo: deactivate schema S (activation #N): whether ORD
     * served it before its end is unknown (...), S may have stayed active to its end`. Undefined
     * when none is left, when ORD's exit was read, or for an undo whose supervisor's end was not read
     * after it (the run may still be going: an undo in flight is no undo unserved).
     */
    atRecordsEnd(): UnservedUndos | undefined {
        if (this.ordEnded) return undefined;
        const left = this.take((u) => u.senderEnded === true);
        if (!left) return undefined;
        return {
            schemas: left.schemas,
            monoNs: left.monoNs,
            text: `${this.runStopping ? 'while the run stopped: ' : ''}ORD's log ends with no exit record (it was killed or terminated: the launcher's output says which) ` +
                `and no answer to ${left.words}: whether ORD served it before its end is unknown (a module killed loses the records it had not written, ` +
                `unless contract-launch wrote them from its log buffers), ${left.schemas.join(', ')} may have stayed active to its end`,
        };
    }

    /** The undos left (those `which` takes: all by default), their words and schemas, forgotten. */
    private take(which: (u: Undo) => boolean = () => true): { words: string; schemas: string[]; monoNs: string } | undefined {
        const undos = [...this.unserved.values()].filter(which);
        if (!undos.length) return undefined;
        this.unserved.clear();
        this.lastUndoOf.clear();
        return { words: undos.map((u) => u.words).join(', '), schemas: [...new Set(undos.map((u) => u.schema))], monoNs: undos[undos.length - 1]!.monoNs };
    }
}

/**
 * What the flows did, as `contract trace` tells it (@contract-studio/build-service/trace, its
 * StoryTeller's flowLines): the event flows whose posts waited for room in their subscriber's full
 * mailbox (EventWaits: its first streak told where it happens), and, at the records' end, the data
 * flows ORD connected that delivered nothing or far less than their reader read (DataFlowUse).
 *
 * The Monitor reads most lines in place (line-scan.ts) without parsing them: the kinds DataFlowUse
 * counts that are read so (`data_posted`, `data_received`, `ord_release`) reach it as a record
 * view made of the line's fields, one object reused for every line (no allocation per record but
 * the time's digits); every other line reaches it with its time only, which is the run's end so far.
 */
import { DataFlowUse, EventWaits, type KnownRecord } from '@contract-studio/build-service/trace';
import { digitsValue, nameIn, scanned } from './line-scan.js';
import { numberOf } from './hot-line.js';

/** The `event_waited` records are parsed (one per streak of waits: few), so that EventWaits reads them whole. */
export const PARSED_FLOW_KINDS: ReadonlySet<string> = new Set(['event_waited']);

export class FlowFindings {
  private readonly waits = new EventWaits();
  private readonly use = new DataFlowUse();
  /** The record view of a line read in place (scannedLine): reused. */
  private readonly postedFields: Record<string, string | number> = {};
  private readonly view: KnownRecord = { kind: '', monoNs: '0', wallTime: '', module: '', peer: '', port: null, size: 0, detail: '', fields: {} };

  /**
   * A parsed record: for an event flow's first `event_waited` record, trace's line for it
   * (`events PSH:0 -> BIN:0 waited for room in BIN's full mailbox 5 times in 1.18 s (...)`), else undefined.
   */
  see(k: KnownRecord): string | undefined {
    this.use.see(k);
    return this.waits.see(k);
  }

  /** The line text[from, to) that scanLine accepted and the model reads in place (`scanned` holds its commas, time and kind). */
  seeScanned(text: string, from: number, to: number): void {
    const c = scanned.comma, v = this.view;
    v.kind = scanned.kind;
    v.monoNs = text.slice(from, c[0]!);
    if (v.kind === 'data_posted' || v.kind === 'data_received' || v.kind === 'ord_release') {
      v.module = nameIn(text, c[1]! + 1, c[2]!);
      v.peer = nameIn(text, c[3]! + 1, c[4]!);
      v.port = c[5]! > c[4]! + 1 ? digitsValue(text, c[4]! + 1, c[5]!) : null;
      const toPort = v.kind === 'data_posted' ? numberOf(text, c[6]! + 1, to, 'to_port') : undefined;
      if (toPort === undefined) v.fields = NO_FIELDS;
      else {
        this.postedFields['to_port'] = toPort;
        v.fields = this.postedFields;
      }
    } else {
      v.module = '';
      v.peer = '';
      v.port = null;
      v.fields = NO_FIELDS;
    }
    this.use.see(v);
  }

  /** The data flows' lines at the records' end (silent, then sparse, in flow order), in trace's words. */
  endLines(): string[] {
    return this.use.lines();
  }
}

const NO_FIELDS: Record<string, string | number> = Object.freeze({}) as Record<string, string | number>;


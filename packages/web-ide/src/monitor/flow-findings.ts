/**
 * What the flows did, as `contract trace` tells it (@contract-studio/build-service/trace, its
 * StoryTeller's flowLines): the event flows whose posts waited for room in their subscriber's full
 * mailbox (EventWaits: its first streak told where it happens), and, at the records' end, the data
 * flows ORD connected that delivered nothing or far less than their reader read (DataFlowUse).
 *
 * The Monitor reads most lines in place (line-scan.ts) without parsing them: the kinds DataFlowUse
 * counts that are read so (`data_posted`, `data_received`, `ord_release`, a delivered
 * `event_posted`) reach it as a record view made of the line's fields, one object reused for every
 * line, without their time (DataFlowUse reads a time only at a connect or a disconnect, parsed
 * records). The run's end so far is the latest line's time, kept as where its digits are (the line
 * scan's number compared) and read once, at the records' end: no string nor BigInt per line.
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
  /** The latest line read in place: its time as the scan's number, and where its digits are (read at endLines). */
  private latest = -1;
  private latestText = '';
  private latestFrom = 0;
  private latestTo = 0;

  /**
   * A parsed record: for an event flow's first `event_waited` record, trace's line for it
   * (`events PSH:0 -> BIN:0 waited for room in BIN's full mailbox 5 times in 1.18 s (...)`), else undefined.
   */
  see(k: KnownRecord): string | undefined {
    this.use.see(k);
    return this.waits.see(k);
  }

  /**
   * The records are a simulation's: its modules ran no code, so the data flows and the event flows
   * supervisors connected are not told as having delivered nothing (DataFlowUse.simulated: one line
   * says why instead, shown without ⚠).
   */
  simulated(): void {
    this.use.simulated();
  }

  /** The line text[from, to) that scanLine accepted and the model reads in place (`scanned` holds its commas, time and kind). */
  seeScanned(text: string, from: number, to: number): void {
    const c = scanned.comma, v = this.view, kind = scanned.kind;
    this.seeTimeAt(text, from, c[0]!);
    const posted = kind === 'data_posted' || kind === 'event_posted';
    if (!posted && kind !== 'data_received' && kind !== 'ord_release') return;
    v.kind = kind;
    v.module = nameIn(text, c[1]! + 1, c[2]!);
    v.peer = nameIn(text, c[3]! + 1, c[4]!);
    v.port = c[5]! > c[4]! + 1 ? digitsValue(text, c[4]! + 1, c[5]!) : null;
    v.detail = kind === 'event_posted' && text.endsWith(' failed', to) ? ' failed' : '';
    const toPort = posted ? numberOf(text, c[6]! + 1, to, 'to_port') : undefined;
    if (toPort === undefined) v.fields = NO_FIELDS;
    else {
      this.postedFields['to_port'] = toPort;
      v.fields = this.postedFields;
    }
    this.use.seeFlow(v);
  }

  /** A line's time, its digits text[from, to) (scanned.mono their number): kept when it is the latest so far. */
  private seeTimeAt(text: string, from: number, to: number): void {
    const mono = scanned.mono;
    if (mono < this.latest) return;
    // equal numbers past 2^53 may be different times: their digits decide (equal below it are the same time)
    if (mono === this.latest && (mono <= Number.MAX_SAFE_INTEGER || !laterDigits(text, from, to, this.latestText, this.latestFrom, this.latestTo))) return;
    this.latest = mono;
    this.latestText = text;
    this.latestFrom = from;
    this.latestTo = to;
  }

  /** The data flows' lines at the records' end (silent, then sparse, in flow order), in trace's words. */
  endLines(): string[] {
    if (this.latest >= 0) this.use.seeTime(this.latestText.slice(this.latestFrom, this.latestTo));
    return this.use.lines();
  }
}

const NO_FIELDS: Record<string, string | number> = Object.freeze({}) as Record<string, string | number>;

/** Whether the digits a[af, at) are a later time than b[bf, bt) (both past 2^53: as BigInts, rare). */
function laterDigits(a: string, af: number, at: number, b: string, bf: number, bt: number): boolean {
  return BigInt(a.slice(af, at)) > BigInt(b.slice(bf, bt));
}

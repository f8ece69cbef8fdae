// The Monitor benchmarks' latency meter (monitor-bench.mjs, monitor-live-bench.mjs), run in the
// page. Self-contained: its source is sent to the page as it is (installLatencyMeter).
// With `ide.monitor.measure` on, each snapshot of the live run's worker brings the wall time of
// every record it folded (`walls`: written by the module, or sent by the bench's feed) and of its
// arrival at the worker (`arrived`). The meter counts, per record:
//   arrived   wall -> arrival at the worker
//   shown     wall -> the end of the first frame whose drawn model holds it (looked at in a task
//             queued from the frame callback: it runs after the frame's other callbacks, the
//             panel's among them, and after its paint)
//   early     `shown` for the records of the first EARLY_MS of the stream
// in 0.1 ms bins up to 10 s, so that measuring does not load the page it measures (its loops
// are indexed: a for-of over the Float64Arrays boxed every value, about a third of the page's
// garbage while fed, and so more of its garbage collections).
export function latencyMeter() {
  const BINS = 100_000;
  const EARLY_MS = 5000;
  const bins = { arrived: new Uint32Array(BINS), shown: new Uint32Array(BINS), early: new Uint32Array(BINS) };
  const binOf = (ms) => Math.min(BINS - 1, Math.max(0, Math.round(ms * 10)));
  const waiting = [];
  let first = NaN;
  const meter = {
    received: 0,
    shown: 0,
    /** A worker snapshot (RemoteMonitorModel.onSnapshot) of the drawn model version `version`. */
    snapshot(snap, version) {
      if (!snap.walls?.length) return;
      meter.received += snap.walls.length;
      if (Number.isNaN(first)) first = snap.walls[0];
      const arrived = bins.arrived, walls = snap.walls, at = snap.arrived;
      if (at) for (let i = 0; i < walls.length; i++) arrived[binOf(at[i] - walls[i])]++;
      waiting.push({ version, walls });
    },
    /** After a frame: the records of every snapshot the panel has drawn `model` at are shown now. */
    drawn(panel, model) {
      if (!panel || !model || panel.drawn.model !== model) return;
      const now = Date.now();
      const shown = bins.shown, early = bins.early, earlyEnd = first + EARLY_MS;
      while (waiting.length && waiting[0].version <= panel.drawn.version) {
        const walls = waiting.shift().walls;
        for (let i = 0; i < walls.length; i++) { // indexed: no iterator, no boxed number per record
          const b = binOf(now - walls[i]);
          shown[b]++;
          if (walls[i] < earlyEnd) early[b]++;
        }
        meter.shown += walls.length;
      }
    },
    /** The p-th percentile (ms) of one count: 'arrived', 'shown' or 'early'; NaN when empty. */
    pct(which, p) {
      const b = bins[which];
      const total = b.reduce((a, x) => a + x, 0);
      let k = 0;
      for (let i = 0; i < b.length; i++) if (total && (k += b[i]) >= (total * p) / 100) return i / 10;
      return NaN;
    },
  };
  return meter;
}

/** Defines window.__latencyMeter() in the page. */
export async function installLatencyMeter(page) {
  await page.evaluate(`window.__latencyMeter = ${latencyMeter.toString()};`);
}

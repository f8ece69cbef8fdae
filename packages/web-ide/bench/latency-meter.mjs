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
// in 0.1 ms bins up to 10 s, so that measuring does not load the page it measures.
export function latencyMeter() {
  const BINS = 100_000;
  const EARLY_MS = 5000;
  const bins = { arrived: new Uint32Array(BINS), shown: new Uint32Array(BINS), early: new Uint32Array(BINS) };
  const bin = (which, ms) => bins[which][Math.min(BINS - 1, Math.max(0, Math.round(ms * 10)))]++;
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
      if (snap.arrived) for (let i = 0; i < snap.walls.length; i++) bin('arrived', snap.arrived[i] - snap.walls[i]);
      waiting.push({ version, walls: snap.walls });
    },
    /** After a frame: the records of every snapshot the panel has drawn `model` at are shown now. */
    drawn(panel, model) {
      if (!panel || !model || panel.drawn.model !== model) return;
      const now = Date.now();
      while (waiting.length && waiting[0].version <= panel.drawn.version) {
        for (const w of waiting.shift().walls) {
          bin('shown', now - w);
          if (w < first + EARLY_MS) bin('early', now - w);
          meter.shown++;
        }
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

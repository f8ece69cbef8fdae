// A Chromium trace of every process (browser, renderer, GPU/viz) while a bench runs, to see what
// a late frame waited for: FRAME_TRACE=<file.json> node bench/monitor-bench.mjs records the fed
// phase. startFrameTrace(context, page) starts it; stop(file) writes the trace (Trace Event JSON,
// opens in chrome://tracing or Perfetto). The frame loops mark each late frame with
// performance.mark('late-frame') (blink.user_timing), which lateFrameReport() finds.
// `node bench/frame-trace.mjs <file.json>` prints, for each late frame, the busiest threads of
// every process in its window: whose work filled the gap.
import { createWriteStream, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const CATEGORIES = ['toplevel', 'benchmark', 'blink.user_timing', 'cc', 'viz', 'gpu', 'devtools.timeline', 'disabled-by-default-devtools.timeline.frame'];

export async function startFrameTrace(context, page) {
  const cdp = await context.newCDPSession(page);
  await cdp.send('Tracing.start', { transferMode: 'ReturnAsStream', traceConfig: { recordMode: 'recordAsMuchAsPossible', includedCategories: CATEGORIES } });
  return {
    async stop(file) {
      const complete = new Promise((resolve) => cdp.once('Tracing.tracingComplete', resolve));
      await cdp.send('Tracing.end');
      const { stream, dataLossOccurred } = await complete;
      const out = createWriteStream(file);
      for (;;) {
        const { data, eof, base64Encoded } = await cdp.send('IO.read', { handle: stream, size: 1 << 20 });
        out.write(base64Encoded ? Buffer.from(data, 'base64') : data);
        if (eof) break;
      }
      await cdp.send('IO.close', { handle: stream });
      await new Promise((r) => out.end(r));
      await cdp.detach();
      return { dataLossOccurred };
    },
  };
}

/** For each `late-frame` mark: its gap and, per thread, the time its top-level tasks ran in the gap. */
export function lateFrameReport(trace, top = 6) {
  const events = Array.isArray(trace) ? trace : trace.traceEvents;
  const names = new Map(); // "pid:tid" -> "process/thread"
  const procs = new Map();
  for (const e of events) {
    if (e.ph === 'M' && e.name === 'process_name') procs.set(e.pid, e.args.name);
  }
  for (const e of events) {
    if (e.ph === 'M' && e.name === 'thread_name') names.set(`${e.pid}:${e.tid}`, `${procs.get(e.pid) ?? e.pid}/${e.args.name}`);
  }
  const marks = events.filter((e) => e.name === 'late-frame' && (e.ph === 'R' || e.ph === 'I' || e.ph === 'n' || e.ph === 'b'));
  const tasks = events.filter((e) => e.ph === 'X' && e.dur > 0 && (e.cat.includes('toplevel') || e.name === 'ThreadControllerImpl::RunTask'));
  return marks.map((m) => {
    const gapMs = Number(m.args?.data?.detail ? JSON.parse(m.args.data.detail) : 0);
    const end = m.ts, start = end - gapMs * 1000;
    const busy = new Map();
    for (const t of tasks) {
      const a = Math.max(start, t.ts), b = Math.min(end, t.ts + t.dur);
      if (b > a) {
        const key = names.get(`${t.pid}:${t.tid}`) ?? `${t.pid}:${t.tid}`;
        const cur = busy.get(key) ?? { ms: 0, longest: 0, name: '' };
        cur.ms += (b - a) / 1000;
        if (t.dur > cur.longest) { cur.longest = t.dur; cur.name = t.args?.src_func ?? t.name; }
        busy.set(key, cur);
      }
    }
    const threads = [...busy].sort((x, y) => y[1].ms - x[1].ms).slice(0, top)
      .map(([k, v]) => `${k} ${v.ms.toFixed(1)} ms (longest ${(v.longest / 1000).toFixed(1)} ms ${v.name})`);
    const chromiumMs = [...busy.values()].reduce((a, v) => a + v.ms, 0);
    return { atMs: Math.round(end / 1000), gapMs, chromiumMs, threads };
  });
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const trace = JSON.parse(readFileSync(process.argv[2], 'utf8'));
  const report = lateFrameReport(trace);
  if (!report.length) console.log('no late frame in this trace');
  for (const r of report)
    console.log(`late frame at ${r.atMs} ms, gap ${r.gapMs.toFixed(1)} ms, Chromium's threads busy ${r.chromiumMs.toFixed(1)} ms in all\n  ${r.threads.join('\n  ')}`);
}

// What the live run's Web Worker, or the page, allocates or spends on the CPU while the panel benchmark feeds it:
// WORKER_ALLOC=1 (PAGE_ALLOC=1) node bench/monitor-bench.mjs samples the worker's (the page's main
// thread's) heap allocations (V8's sampling heap profiler, objects already collected included) for
// the fed phase, and prints the MB a second and the functions that allocate most. Garbage in the
// worker is work on a CPU the compositor also needs on a two-CPU machine; the page's sets how often
// its collections come (docs/monitor-performance.md "Traced on 2026-12-02").
// startWorkerAlloc(context, page) attaches before the worker starts; startPageAlloc(context, page)
// samples the page itself; begin() starts sampling, stop() returns the report. WORKER_CPU=1
// (startWorkerCpu) samples the worker's CPU time instead: busy and collector ms a second.

/** A DevTools session on the first worker the page starts from now on: attached() waits for it, send() talks to it. */
async function workerSession(context, page) {
  const cdp = await context.newCDPSession(page);
  // the workers' session ids, as they attach (messages go through the page's session: not flattened)
  const workers = [];
  let worker;
  let nextId = 1;
  const pending = new Map();
  let attachedOne = () => undefined;
  cdp.on('Target.attachedToTarget', (e) => {
    if (e.targetInfo.type !== 'worker') return;
    workers.push(e.sessionId);
    attachedOne();
  });
  cdp.on('Target.receivedMessageFromTarget', (e) => {
    const m = JSON.parse(e.message);
    const p = pending.get(m.id);
    if (!p) return;
    pending.delete(m.id);
    if (m.error) p.reject(new Error(m.error.message));
    else p.resolve(m.result);
  });
  const send = (method, params = {}) => new Promise((resolve, reject) => {
    const id = nextId++;
    pending.set(id, { resolve, reject });
    cdp.send('Target.sendMessageToTarget', { sessionId: worker, message: JSON.stringify({ id, method, params }) }).catch(reject);
  });
  await cdp.send('Target.setAutoAttach', { autoAttach: true, waitForDebuggerOnStart: false, flatten: false });
  await new Promise((r) => setTimeout(r, 300)); // the workers already there (an earlier live run's) attach now
  const before = workers.length;
  return {
    async attached() {
      if (workers.length <= before) await new Promise((resolve) => { attachedOne = resolve; });
      worker = workers[before];
    },
    send,
    detach: () => cdp.detach(),
  };
}

export async function startWorkerAlloc(context, page) {
  const w = await workerSession(context, page);
  const sampler = heapSampler(w.send, w.detach);
  return {
    /** Starts sampling the first worker started since (call once the page follows the fed run). */
    async begin() {
      await w.attached();
      await sampler.begin();
    },
    stop: sampler.stop,
  };
}

/**
 * WORKER_CPU=1: the worker's CPU time, from V8's sampling CPU profiler (a sample every 200 µs):
 * ms a second busy (all but idle), of which in the collector, and the functions with most self time.
 */
export async function startWorkerCpu(context, page) {
  const w = await workerSession(context, page);
  let started;
  return {
    async begin() {
      await w.attached();
      await w.send('Profiler.enable');
      await w.send('Profiler.setSamplingInterval', { interval: 200 });
      await w.send('Profiler.start');
      started = performance.now();
    },
    async stop(top = 8) {
      const { profile } = await w.send('Profiler.stop');
      const seconds = (performance.now() - started) / 1000;
      await w.detach().catch(() => undefined);
      const nodes = new Map(profile.nodes.map((n) => [n.id, n]));
      const self = new Map();
      let busy = 0;
      let gc = 0;
      profile.samples.forEach((id, i) => {
        const f = nodes.get(id).callFrame;
        const dt = profile.timeDeltas[i] / 1000;
        if (f.functionName === '(idle)') return;
        busy += dt;
        if (f.functionName === '(garbage collector)') gc += dt;
        const name = frameName(f);
        self.set(name, (self.get(name) ?? 0) + dt);
      });
      const r = (x) => Math.round(x * 10) / 10;
      return { busyMsPerS: r(busy / seconds), gcMsPerS: r(gc / seconds), seconds: Math.round(seconds), top: [...self].sort((a, b) => b[1] - a[1]).slice(0, top).map(([k, v]) => `${r(v / seconds)} ms/s ${k}`) };
    },
  };
}

export async function startPageAlloc(context, page) {
  const cdp = await context.newCDPSession(page);
  return heapSampler((method, params) => cdp.send(method, params), () => cdp.detach());
}

/** V8's sampling heap profiler over `send` (a DevTools session's): begin(), then stop() gives the report. */
function heapSampler(send, detach) {
  let started;
  return {
    async begin() {
      await send('HeapProfiler.enable');
      await send('HeapProfiler.startSampling', { samplingInterval: 16384, includeObjectsCollectedByMajorGC: true, includeObjectsCollectedByMinorGC: true });
      started = performance.now();
    },
    async stop(top = 8) {
      const { profile } = await send('HeapProfiler.stopSampling');
      const seconds = (performance.now() - started) / 1000;
      await detach().catch(() => undefined);
      return report(profile, seconds, top);
    },
  };
}

/** MB allocated a second, and the functions that allocated most (self size). */
function report(profile, seconds, top) {
  const byFunction = new Map();
  let total = 0;
  const walk = (node) => {
    const name = frameName(node.callFrame);
    total += node.selfSize;
    if (node.selfSize) byFunction.set(name, (byFunction.get(name) ?? 0) + node.selfSize);
    for (const c of node.children) walk(c);
  };
  walk(profile.head);
  const mb = (b) => Math.round(b / 1e5) / 10;
  return { mbPerS: Math.round((total / 1e6 / seconds) * 10) / 10, seconds: Math.round(seconds), top: [...byFunction].sort((a, b) => b[1] - a[1]).slice(0, top).map(([k, v]) => `${mb(v)} MB ${k}`) };
}

/** A profile's call frame as the reports name it: function, script file, line. */
function frameName(f) {
  return `${f.functionName || '(top)'} ${f.url.split('/').pop()}:${f.lineNumber + 1}`;
}

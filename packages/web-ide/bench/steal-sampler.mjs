// The hypervisor's share of the late frames. On a virtual machine the host takes CPU time from
// the guest (/proc/stat's `steal` column): a frame can be late with no work of the page's behind
// it. startStealSampler() runs a child process that reads every CPU's stolen time every
// SAMPLE_MS; lateFramesAndSteal() then says how many late frames had time stolen during them, next
// to the same share of the frames that were on time (the chance of a steal in any window of that
// length). /proc/stat counts in 10 ms ticks and is read every SAMPLE_MS, so a window is widened by
// a tick before and a tick and a sample after.
// Used by monitor-bench.mjs and monitor-live-bench.mjs.
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const SAMPLE_MS = 5;
const TICK_MS = 10; // USER_HZ
/** A frame later than this (ms) is late: more than one and a half vsync intervals. */
export const LATE_FRAME_MS = 25;

/** Stolen ms per CPU, in /proc/stat order; [] where /proc/stat has no steal column. */
function readSteal() {
  const out = [];
  for (const line of readFileSync('/proc/stat', 'utf8').split('\n')) {
    const m = /^cpu\d+ (.*)$/.exec(line);
    if (m) out.push((Number(m[1].split(' ')[7]) || 0) * TICK_MS);
  }
  return out;
}

/** Starts sampling; stop() resolves with [epoch ms, ms stolen since the sample before (all CPUs)] at each change. */
export function startStealSampler() {
  const child = spawn(process.execPath, [fileURLToPath(import.meta.url), '--sample'], { stdio: ['pipe', 'pipe', 'inherit'] });
  let out = '';
  child.stdout.setEncoding('utf8').on('data', (d) => (out += d));
  const exited = new Promise((resolve) => child.on('exit', resolve));
  return {
    async stop() {
      child.stdin.end();
      await exited;
      try {
        return JSON.parse(out);
      } catch {
        return [];
      }
    },
  };
}

/**
 * frames: [end epoch ms, gap ms] of each animation frame; steals: startStealSampler's samples.
 * How many frames were late, how many of those had time stolen (any CPU) in their window, the
 * same share for the frames on time, and the ms stolen a second over the frames' span.
 */
export function lateFramesAndSteal(frames, steals) {
  const at = steals.map((s) => s[0]);
  /** ms stolen in [from, to]. */
  const stolen = (from, to) => {
    let sum = 0;
    for (let i = lowerBound(at, from); i < at.length && at[i] <= to; i++) sum += steals[i][1];
    return sum;
  };
  let late = 0;
  let lateStolen = 0;
  let onTime = 0;
  let onTimeStolen = 0;
  for (const [end, gap] of frames) {
    const s = stolen(end - gap - TICK_MS, end + TICK_MS + SAMPLE_MS) > 0;
    if (gap > LATE_FRAME_MS) {
      late++;
      if (s) lateStolen++;
    } else {
      onTime++;
      if (s) onTimeStolen++;
    }
  }
  const span = frames.length ? (frames.at(-1)[0] - (frames[0][0] - frames[0][1])) / 1000 : 0;
  return {
    late,
    lateStolen,
    onTimeStolenShare: onTime ? onTimeStolen / onTime : 0,
    stealMsPerS: span > 0 ? stolen(frames[0][0] - frames[0][1], frames.at(-1)[0]) / span : 0,
  };
}

function lowerBound(xs, x) {
  let lo = 0;
  let hi = xs.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] < x) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

if (process.argv[2] === '--sample') {
  const samples = [];
  let last = readSteal();
  const timer = setInterval(() => {
    const now = readSteal();
    let d = 0;
    for (let i = 0; i < now.length; i++) d += now[i] - (last[i] ?? now[i]);
    if (d > 0) samples.push([Date.now(), d]);
    last = now;
  }, SAMPLE_MS);
  process.stdin.resume();
  process.stdin.on('end', () => {
    clearInterval(timer);
    process.stdout.write(JSON.stringify(samples));
  });
}

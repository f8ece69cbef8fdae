/**
 * Long work on the page's thread, done in slices with the page's other work between them: a
 * generator that yields often (every few hundred lines) is run for SLICE_MS at a time, then the page
 * draws a frame and answers a key before the next slice. The Monitor's replays use it (building a
 * recorded run's model, reading a trace file's JSON lines).
 */

/** Work done between two frames, at most (a frame at 60 Hz is 16.7 ms). */
export const SLICE_MS = 8;

/** Runs `steps` to its end in slices of `sliceMs`, letting the page draw between them; resolves its result. */
export async function runSliced<T>(steps: Generator<void, T>, sliceMs = SLICE_MS): Promise<T> {
  let until = performance.now() + sliceMs;
  let step = steps.next();
  for (; !step.done; step = steps.next()) {
    if (performance.now() < until) continue;
    await yieldToPage();
    until = performance.now() + sliceMs;
  }
  return step.value;
}

/**
 * Lets the page draw a frame and handle input, and comes back as soon as it has: a message to
 * itself, not setTimeout (which a browser holds back at least 4 ms after a few nested calls: half
 * the build's time was spent waiting).
 */
export function yieldToPage(): Promise<void> {
  return new Promise((resolve) => {
    const channel = new MessageChannel();
    channel.port1.onmessage = () => {
      channel.port1.close();
      resolve();
    };
    channel.port2.postMessage(undefined);
  });
}

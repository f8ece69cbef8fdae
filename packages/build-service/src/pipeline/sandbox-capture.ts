/**
 * A short command of the service's own run in a job's sandbox after its steps (addr2line on a
 * crashed module's executable: crash-reports.ts), its stdout read up to a bound: the sandbox's
 * output is untrusted, and the command is killed at its time bound. Never throws.
 */
import type { Readable } from 'node:stream';
import type { Sandbox, SandboxCommand } from '../sandbox/types.js';

/** Up to `maxChars` of the command's stdout, or null when it could not run, failed or took longer than `timeoutMs`. */
export async function captureInSandbox(sandbox: Sandbox, cmd: SandboxCommand, maxChars: number, timeoutMs: number): Promise<string | null> {
  let proc;
  try {
    proc = await sandbox.start(cmd);
  } catch {
    return null;
  }
  const out = readUpTo(proc.stdout, maxChars);
  proc.stderr.on('data', () => {}).on('error', () => {});
  let timedOut = false;
  const timer = setTimeout(() => {
    timedOut = true;
    proc.kill().catch(() => {});
  }, timeoutMs);
  try {
    const exit = await proc.done;
    const text = await out;
    return !timedOut && exit.exitCode === 0 ? text : null;
  } catch {
    return null;
  } finally {
    clearTimeout(timer);
  }
}

/** The stream's text up to `maxChars` characters (the rest drained, not kept). */
function readUpTo(stream: Readable, maxChars: number): Promise<string> {
  return new Promise((resolve) => {
    let text = '';
    stream.setEncoding('utf8');
    stream.on('data', (chunk: string) => {
      if (text.length < maxChars) text += chunk.slice(0, maxChars - text.length);
    });
    stream.on('error', () => resolve(text));
    stream.on('close', () => resolve(text));
    stream.on('end', () => resolve(text));
  });
}

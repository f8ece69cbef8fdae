/**
 * What a client may send on a job's WebSocket (GET /api/jobs/:id/ws, docs/build-service-api.md
 * "Events"): one text frame, `{"type":"cancel"}` (other fields are ignored), which cancels the job
 * as DELETE /api/jobs/:id does. Anything else (a binary frame, text that is not JSON, JSON that is
 * not an object, an object whose `type` is not "cancel") is answered with one error frame,
 * `{"type":"error","code":"bad_frame","error":"..."}`, and the socket stays open: a client's
 * mistake is said to it, never silently ignored, and costs no one the job's stream.
 * (Ping, pong and close are the WebSocket protocol's own frames: the `ws` library answers them.)
 */

/** The frame types a client may send. */
export const CLIENT_FRAME_TYPES = ['cancel'] as const;

/** The `code` of the error frame answering a client frame the service does not take. */
export const BAD_FRAME_CODE = 'bad_frame';

/** A client frame read: a cancel, or why it was refused (the error frame's text). */
export type ClientFrame = { type: 'cancel' } | { type: 'refused'; error: string };

/** At most this many characters of a refused frame are quoted back. */
const QUOTED_CHARS = 60;

function quoted(text: string): string {
  return JSON.stringify(text.length > QUOTED_CHARS ? `${text.slice(0, QUOTED_CHARS)}...` : text);
}

const ACCEPTED = `the only frame a client may send is the text frame {"type":"cancel"}`;

/** Reads one data frame a client sent. */
export function readClientFrame(data: Buffer | ArrayBuffer | Buffer[], isBinary: boolean): ClientFrame {
  if (isBinary) return { type: 'refused', error: `binary frame refused: ${ACCEPTED}` };
  const text = Buffer.isBuffer(data) ? data.toString('utf8') : Array.isArray(data) ? Buffer.concat(data).toString('utf8') : Buffer.from(data).toString('utf8');
  let msg: unknown;
  try {
    msg = JSON.parse(text);
  } catch (e) {
    return { type: 'refused', error: `frame ${quoted(text)} is not JSON (${(e as Error).message.slice(0, 120)}): ${ACCEPTED}` };
  }
  if (!msg || typeof msg !== 'object' || Array.isArray(msg)) return { type: 'refused', error: `frame ${quoted(text)} is not a JSON object: ${ACCEPTED}` };
  const type = (msg as { type?: unknown }).type;
  if (type === 'cancel') return { type: 'cancel' };
  const named = type === undefined ? 'has no "type"' : `has the unknown type ${quoted(typeof type === 'string' ? type : JSON.stringify(type) ?? String(type))}`;
  return { type: 'refused', error: `frame ${named}: ${ACCEPTED}` };
}

/** The error frame answering a refused client frame (not a job event: no seq, never inside a batch's array). */
export function clientErrorFrame(error: string): string {
  return JSON.stringify({ type: 'error', code: BAD_FRAME_CODE, error });
}

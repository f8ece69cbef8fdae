/**
 * The one reading of a JSON request body, for the build service (POST /api/jobs) and the IDE
 * server's own routes (its workspace file API, Generate, rename...): text that is not JSON is
 * refused with the parser's own error named (`invalid JSON: Unexpected token ...`), so a client
 * learns where its body is broken; both answer it `400 { code: "bad_request", error }`.
 */

/** The refusal of a body that is JSON but not an object, where an object is asked for. */
export const JSON_BODY_NOT_OBJECT = 'the body must be a JSON object';

/** At most this many characters of the parser's error are quoted. */
const PARSER_ERROR_CHARS = 200;

/** The body's JSON value, or why it is not JSON (`invalid JSON: <the parser's error>`). */
export function parseJsonBody(text: string): { ok: true; value: unknown } | { ok: false; error: string } {
  try {
    return { ok: true, value: JSON.parse(text) as unknown };
  } catch (e) {
    return { ok: false, error: `invalid JSON: ${(e as Error).message.slice(0, PARSER_ERROR_CHARS)}` };
  }
}

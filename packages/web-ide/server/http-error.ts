/** An error that maps to an HTTP status and a message meant for the user. */
export class HttpError extends Error {
  constructor(
    readonly status: number,
    message: string,
    /** Extra fields of the JSON error answer (besides `error`), e.g. the region and line a save was refused for. */
    readonly details?: Record<string, unknown>,
  ) {
    super(message);
    this.name = 'HttpError';
  }
}

import { ApiError } from '../api.js';
import { toast } from '../util/toast.js';

/** A failed operation as an error notice (the server's message when it gave one). */
export function reportError(e: unknown): void {
  toast('error', e instanceof ApiError ? e.message : String(e));
}

/// <reference lib="webworker" />
/**
 * Entry of the Web Worker that follows one live run's trace (live-follower.ts): the page's
 * main thread then only draws (docs/watching-a-run.md "Where the work is done").
 */
import { LiveFollower } from './live-follower.js';
import type { ToFollower } from './live-follow-protocol.js';

const scope = self as unknown as DedicatedWorkerGlobalScope;
const follower = new LiveFollower((m) => scope.postMessage(m), (url) => new WebSocket(url));
scope.onmessage = (e: MessageEvent<ToFollower>) => follower.handle(e.data);

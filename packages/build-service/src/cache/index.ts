/**
 * `@contract-studio/build-service/cache`: where the persistent cache lives, whether it can be
 * trusted, and the cross-process lock, without the rest of the build service (no Docker client, no
 * pipeline). The simulator keeps its harnesses under the same root (`<cache>/sim/`,
 * docs/simulation.md §3) and locks their builds with the same flock(2) helper.
 */
export { CACHE_DIR_ENV, CACHE_ENTRIES, CACHE_ENTRY_NAMES, CacheRefusedError, checkCacheEntry, prepareCacheDir, resolveCacheDir, type CacheDirChoice } from './cache-dir.js';
export { acquireProjectLock, type ProjectLock } from './project-lock.js';
export { ABANDONED_AFTER_MS, removeAbandonedBuilds } from './abandoned-builds.js';
export { CACHE_ENTRY_IDLE_MS, markUsed, removeLeastRecentlyUsed } from './least-recently-used.js';
export { SERVICE_BOUNDS } from '../limits.js';

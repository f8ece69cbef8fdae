/**
 * @contract-studio/build-service — sandboxed gcc build + run of Cactal projects with live streams.
 * See README.md, docs/build-service-api.md (HTTP API) and docs/sandbox.md (sandboxes, limits).
 */
export { createBuildServer, DEFAULT_PORT, type BuildServer, type BuildServerOptions } from './server.js';
export { JobService, DEFAULT_RUNTIME_SOURCE, type BuildServiceOptions } from './job-service.js';
export { ServiceError } from './service-errors.js';
export { clearCache } from './cache/clear-cache.js';
export { CACHE_DIR_ENV, CACHE_ENTRY_NAMES, CacheRefusedError, prepareCacheDir, resolveCacheDir, type CacheDirChoice } from './cache/cache-dir.js';
export { DEFAULT_LIMITS, CANCEL_DEADLINE_MS, describeLimitHit, LimitsError, mergeLimits, type Limits, type LimitHit, type Mechanism } from './limits.js';
export type { Job, JobRequest, JobResult } from './pipeline/job.js';
export type { JobEvent, JobStatus, JobStep, LineEvent } from './pipeline/job-events.js';
export { renderDiagnostic, type GccDiagnostic } from './pipeline/gcc-diagnostics.js';
export type { ProtectedRegion } from './pipeline/protected-regions.js';
export type { Sandbox, SandboxChoice, SandboxName, Mechanisms } from './sandbox/types.js';
export { SandboxRegistry, SandboxUnavailableError } from './sandbox/select.js';
export { ARTIFACT_BOUNDS, artifactBytes, type Artifact, type ArtifactBounds, type RunArtifacts, type SkippedArtifact } from './pipeline/artifacts.js';
export { describeIssues, type RunIssue, type RunIssueKind } from './pipeline/run-issues.js';
export { LauncherCrashes, failureWords, crashMeaningText, type LauncherFailure } from './pipeline/launcher-crashes.js';
export { CRASH_MARK, crashSiteOfLine } from './pipeline/crash-reports.js';
export { foreignMakefilesMessage } from './pipeline/foreign-makefiles.js';
export { installedRuntimeProblem } from './pipeline/runtime-cache.js';
export type { SweepPolicy, SweepReport } from './sandbox/docker-sweep.js';

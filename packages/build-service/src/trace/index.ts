/**
 * The run-time trace model (docs/runtime-api.md "Trace records"): the record kinds, the
 * browser-safe reader of a run's CSV logs, and the readable story. Imported by the CLI
 * (`contract trace`, `contract run --trace`) as `@contract-studio/build-service/trace`.
 */
export { TRACE_KINDS, traceKind, isUserEventName, type TraceKind, type TraceArea } from './record-kinds.js';
export { parseTrace, parseLogFile, parseRecordLine, parseStreamedLine, recordOfLine, unendedLine, recordLineEnd, parseCause, ownString, moduleOfLog, moduleNamedByLog, isLogFileName, twinLogs, TWIN_LOGS_WHY, foreignRecordReason, CSV_HEADER, NOT_A_LOG_WHY, isLogHeaderIn, notALogRecord, MAX_LINE_CHARS, type LogFile } from './parse.js';
export { splitCsvLine, csvField } from './csv-line.js';
export { traceFileToLogs, traceFileToLogsSteps, recordOfJsonLine, traceFileItemOfJsonLine, jsonLineToCsv, MAX_JSON_LINE_CHARS, MAX_TRACE_FILE_MODULES, type TraceFileLogs, type JsonLineRead } from './jsonl.js';
export { isDigitsIn, isModuleNameIn, isPlainIntegerIn, spaceIn, wordValueIn, hasWordIn } from './field-checks.js';
export { schedulerLineFields } from './text-lines.js';
export { skippedReleasesOf, overrunningAfter, missedTicksOf } from './ord-counts.js';
export { durationText } from './duration-text.js';
export { confirmingHold, flowHoldName, type ConfirmingHold } from './action-holds.js';
export { launcherEndLine, endedOnItsOwn, type LauncherEnd } from './launcher-end-line.js';
export { LAUNCHER_LINES_FILE, MAX_LAUNCHER_LINES_BYTES, MAX_LAUNCHER_LINES, launcherLinesOfFile, LauncherLinesQueue, type LauncherFileLine } from './launcher-lines-file.js';
export { LAUNCHER_LINE_KIND, launcherLineJson, launcherLineOfJson, isLauncherLine, type LauncherLineJson, type LauncherLineItem } from './launcher-line-record.js';
export type { EventHandlingFigures } from './event-handling.js';
export { DurationQuantiles } from './duration-quantiles.js';
export { renderStory, StoryTeller, CUT_RECORD, crashText, unheardEventText, type SchemaFigures, type NamedSchemaFigures, dataDropReason, userRecordText, keptRequestsText, askedToStopText, holdText, ownRunEndText, readableCause, missWaitText, missCriticalDelayNs, earlyFinish, sinceTickText, type EarlyAck, type EarlyFinish, priorityText, LATE_RELEASE_SHARE, stuckSaysGone, ignoredUndo, LATE_RELEASE_NS, STORY_FOLLOWED } from './story.js';
export { DataFlowUse, SILENT_FLOW_MIN_NS, SIMULATED_FLOWS_WHY, SPARSE_FLOW_RATIO } from './data-flow-use.js';
export { SupervisorFlowUse } from './supervisor-flow-use.js';
export { EventWaits, flowWaitsLine, waitTotalsText, type FlowWaitTotals } from './event-waits.js';
export { UnmatchedEvents, changedNoRule, receivedValue } from './unmatched-events.js';
export { ProducerChanges, isInterleave } from './producer-changes.js';
export { MinHeap } from './min-heap.js';
export { TRACE_LINES_KEPT } from './replay-bound.js';
export { renderTraceTable, withTraceTable } from './render-doc.js';
export { allFieldKeys, fieldJsonType, fieldKeysOf, type FieldJsonType } from './field-types.js';
export { isRule, isUnknown, countRecord, type RecordCounts, type TraceRecord, type TraceRecordBase, type RuleRecord, type RuleCause, type KnownRecord, type UnknownRecord } from './records.js';
export { encodeTraceRecords, decodeTraceRecords, forEachTraceRecord, forEachTraceLine, TraceWireError, type TraceWire, type TraceLine } from './wire.js';
export { LogClock, LogClocks, monoBeyondInt64, monoTextProblem, wallTimeMs, posingAs, posingText, ORD_MODULE, BACK_TOLERANCE_NS, JUMP_CHECKED_NS, WALL_TOLERANCE_NS } from './log-clock.js';
export { UndosToOrd, type UnservedUndos } from './undos-to-ord.js';
export { receiverGone, type ReceiverGoneWay } from './receiver-gone.js';
export type { LauncherToldEnd } from './ended-mid-run.js';
export { ModuleCpu, type ModuleCpuFigure } from './module-cpu.js';
export { EngineCpu, type EngineCpuFigure } from './engine-cpu.js';

/**
 * `@contract-studio/simulator/trace`: a simulation's steps as the run-time trace records (browser-safe:
 * the IDE's Monitor and `contract simulate --trace` use the same conversion).
 */
export { stepsToTrace, traceStepOf, actionAsLogged, type TraceStep } from './steps-to-trace.js';
export { actionLines, type ActionLine } from './action-lines.js';

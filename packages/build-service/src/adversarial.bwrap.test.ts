/** Adversarial jobs in bwrap with cgroup v1 limits (see test-support/adversarial-suite.ts). */
import { adversarialSuite } from './test-support/adversarial-suite.js';

adversarialSuite('bwrap', 'cgroup-v1');

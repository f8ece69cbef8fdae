import { describe, expect, it } from 'vitest';
import { addLimitOption, emptyLimitOptions } from './limit-option.js';

describe('--limit NAME=VALUE', () => {
    it('reads a name and a positive number, keeping the text as written', () => {
        const o = emptyLimitOptions();
        expect(addLimitOption(o, 'processes=512')).toBeUndefined();
        expect(addLimitOption(o, 'runSeconds=.5')).toBeUndefined();
        expect(addLimitOption(o, 'memoryMiB=1024.0')).toBeUndefined();
        expect({ ...o.limits }).toEqual({ processes: 512, runSeconds: 0.5, memoryMiB: 1024 });
        expect({ ...o.limitTexts }).toEqual({ processes: '512', runSeconds: '.5', memoryMiB: '1024.0' });
    });

    it('refuses what is no NAME=VALUE with a positive number', () => {
        for (const bad of [undefined, '', 'processes', 'processes=', 'processes=0', 'processes=-1', 'processes=1e3', '=5', '9x=1']) {
            expect(addLimitOption(emptyLimitOptions(), bad), String(bad)).toMatch(/^--limit needs NAME=VALUE with a positive number/);
        }
    });

    it('a name __proto__ is a name like another (left to the service to refuse as unknown)', () => {
        const o = emptyLimitOptions();
        expect(addLimitOption(o, '__proto__=1')).toBeUndefined();
        expect(Object.keys(o.limits)).toEqual(['__proto__']);
    });
});

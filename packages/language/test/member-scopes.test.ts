/**
 * A supervision function's variables (locals, the supervisor's port variables, parameters) and a
 * datatype's fields are described once per workspace build, however many references name them:
 * the 350-line supervisor of the field-sized architecture (bench/large-supervisor-architecture.js)
 * has hundreds of variable references, and each one described every local and port of its
 * function again before the scopes were kept (scoping/member-scopes.ts).
 */
import { AstUtils, EmptyFileSystem, type AstNode } from 'langium';
import { describe, expect, it } from 'vitest';
import { generateLargeSupervisorArchitecture, LARGE_SUPERVISOR_FILE } from '../bench/large-supervisor-architecture.js';
import { createCactalServices } from '../src/cactal-module.js';
import { isField, isLocalVariable, isPort, isSupervisor, isVariableRef } from '../src/generated/ast.js';
import { build } from './helpers.js';

describe('member scopes', () => {
    it('describe each variable and field once per build, not once per reference', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const provider = services.workspace.AstNodeDescriptionProvider;
        const described = new Map<AstNode, number>();
        const original = provider.createDescription.bind(provider);
        provider.createDescription = (node, name, document) => {
            // a port named by its index (`:3`) is another scope; count the descriptions by name
            if ((isLocalVariable(node) || isPort(node) || isField(node)) && name === node.name) described.set(node, (described.get(node) ?? 0) + 1);
            return original(node, name, document);
        };
        const built = await build(Object.fromEntries(generateLargeSupervisorArchitecture()), services);
        expect(built.lines).toEqual([]);

        const big = built.docs.get(LARGE_SUPERVISOR_FILE)!;
        const references = AstUtils.streamAllContents(big.parseResult.value).filter(isVariableRef).count();
        const supervisor = big.parseResult.value.elements.find(isSupervisor)!;
        const locals = AstUtils.streamAllContents(supervisor).filter(isLocalVariable).count();
        expect(references).toBeGreaterThan(300);
        // every local is described once, in its function's scope (the old code: once per reference before it)
        const localCounts = [...described].filter(([node]) => isLocalVariable(node) && AstUtils.getContainerOfType(node, isSupervisor) === supervisor).map(([, n]) => n);
        expect(localCounts.length).toBe(locals);
        expect(Math.max(...localCounts)).toBe(1);
        // a port variable once per function that names variables (the functions of the supervisor), a field once
        const portCounts = [...described].filter(([node]) => isPort(node) && AstUtils.getContainerOfType(node, isSupervisor) === supervisor).map(([, n]) => n);
        expect(Math.max(...portCounts)).toBeLessThanOrEqual(supervisor.functions.length);
        const fieldCounts = [...described].filter(([node]) => isField(node)).map(([, n]) => n);
        expect(Math.max(...fieldCounts)).toBe(1);
    });
});

/**
 * Outline (docs/ide.md "Editor services"): datatypes with their fields, function prototypes, modules with their
 * parameters and ports (detail: direction, kind, index, type), schemas with their modules and
 * communications, the scheduler configuration, supervisors with their ports, functions and rules.
 */
import { GrammarUtils, type AstNode, type LangiumDocument } from 'langium';
import type { DocumentSymbolProvider } from 'langium/lsp';
import { SymbolKind, type DocumentSymbol } from 'vscode-languageserver-types';
import {
    isConstant, isDataCommunication, isDataType, isEnumType, isFunctionPrototype, isModule, isSchedulerConfiguration, isSchema, isSupervisor,
    type Communication, type DataType, type FunctionPrototype, type Model, type Module, type Port, type Schema,
    type SchedulerConfiguration, type Supervisor, type SupervisionFunction
} from '../generated/ast.js';
import { communicationsOf, computeTimeNs, localsOf, moduleInstancesOf, parametersOf, periodNs, rulesOf, scheduledModulesOf, scheduledSchemasOf } from '../model/blocks.js';
import { portKind, portsOf } from '../model/ports.js';
import { typeRefText } from '../model/types.js';
import { formatNanoseconds } from '../model/time.js';

export class CactalDocumentSymbolProvider implements DocumentSymbolProvider {
    getSymbols(document: LangiumDocument): DocumentSymbol[] {
        const model = document.parseResult.value as Model;
        return model.elements.flatMap((element) => {
            if (isDataType(element)) return this.symbol(element, element.name, SymbolKind.Struct, 'datatype', this.fields(element));
            if (isEnumType(element)) {
                return this.symbol(element, element.name, SymbolKind.Enum, 'enum',
                    element.members.flatMap((m, i) => this.symbol(m, m.name, SymbolKind.EnumMember, String(i))));
            }
            if (isConstant(element)) return this.symbol(element, element.name, SymbolKind.Constant, `const ${typeRefText(element.type)}`);
            if (isFunctionPrototype(element)) return this.symbol(element, element.name, SymbolKind.Function, this.signature(element));
            if (isModule(element)) return this.module(element);
            if (isSchema(element)) return this.schema(element);
            if (isSchedulerConfiguration(element)) return this.scheduler(element);
            if (isSupervisor(element)) return this.supervisor(element);
            return [];
        });
    }

    private fields(datatype: DataType): DocumentSymbol[] {
        return datatype.fields.flatMap((f) => this.symbol(f, f.name, SymbolKind.Field, typeRefText(f.type)));
    }

    private signature(fn: FunctionPrototype): string {
        return `${typeRefText(fn.returnType)} (${fn.args.map((a) => `${typeRefText(a.type)} ${a.name}`).join(', ')})`;
    }

    private module(module: Module): DocumentSymbol[] {
        const c = computeTimeNs(module);
        const children = [
            ...parametersOf(module).flatMap((p) => this.symbol(p, p.name, SymbolKind.Property, `parameter :${p.index} ${typeRefText(p.type)}`)),
            ...portsOf(module).flatMap((p) => this.port(p.port))
        ];
        return this.symbol(module, module.name, SymbolKind.Class, `${module.kind} module${c !== undefined ? `, C=${formatNanoseconds(c)}` : ''}`, children);
    }

    private port(port: Port): DocumentSymbol[] {
        return this.symbol(port, port.name, portKind(port) === 'event' ? SymbolKind.Event : SymbolKind.Variable,
            `${port.direction} ${portKind(port)} :${port.index} ${typeRefText(port.type)}`);
    }

    private schema(schema: Schema): DocumentSymbol[] {
        const period = periodNs(schema);
        const children = [
            ...schema.parameters.flatMap((p) => this.symbol(p, p.name, SymbolKind.TypeParameter, typeRefText(p.type))),
            ...moduleInstancesOf(schema).flatMap((m) => this.symbol(m, m.module?.$refText ?? '?', SymbolKind.Module, 'module')),
            ...communicationsOf(schema).flatMap((c) => this.symbol(c, this.communicationText(c), SymbolKind.Operator,
                isDataCommunication(c) ? `data * ${c.periodicity ?? 1}` : c.mode.endsWith('*') ? 'event, continuous' : 'event, one shot'))
        ];
        return this.symbol(schema, schema.name, SymbolKind.Namespace, `${schema.kind} schema${period !== undefined ? `, PERIOD=${formatNanoseconds(period)}` : ''}`, children);
    }

    private communicationText(c: Communication): string {
        const arrow = isDataCommunication(c) ? '->' : c.mode.replace('==', '=');
        return `${c.source?.$refText ?? '?'}:${c.sourcePort?.$refText ?? '?'} ${arrow} ${c.target?.$refText ?? '?'}:${c.targetPort?.$refText ?? '?'}`;
    }

    private scheduler(config: SchedulerConfiguration): DocumentSymbol[] {
        const children = [
            ...scheduledModulesOf(config).flatMap((r) => r.$refNode ? this.symbolAt(r.$refNode, r.$refText, SymbolKind.Module, 'scheduled module') : []),
            ...scheduledSchemasOf(config).flatMap((r) => r.$refNode ? this.symbolAt(r.$refNode, r.$refText, SymbolKind.Namespace, 'scheduled schema') : [])
        ];
        return this.symbol(config, 'scheduler configuration', SymbolKind.Object, undefined, children);
    }

    private supervisor(sup: Supervisor): DocumentSymbol[] {
        const children = [
            ...portsOf(sup).flatMap((p) => this.port(p.port)),
            ...sup.functions.flatMap((fn) => this.function(fn))
        ];
        return this.symbol(sup, sup.name, SymbolKind.Class, 'supervisor', children);
    }

    private function(fn: SupervisionFunction): DocumentSymbol[] {
        const children = [
            ...fn.parameters.flatMap((p) => this.symbol(p, p.name, SymbolKind.TypeParameter, `parameter ${typeRefText(p.type)}`)),
            ...localsOf(fn).flatMap((l) => this.symbol(l, l.name, SymbolKind.Variable, `local ${typeRefText(l.type)}`)),
            ...rulesOf(fn).flatMap((r) => this.symbol(r, r.name, SymbolKind.Key, 'rule'))
        ];
        return this.symbol(fn, fn.name, SymbolKind.Method, `(${fn.parameters.map((p) => `${typeRefText(p.type)} ${p.name}`).join(', ')})`, children);
    }

    /** A symbol for a named node: whole node range, name selection range (nothing for a node without CST). */
    private symbol(node: AstNode & { name?: string }, name: string | undefined, kind: SymbolKind, detail?: string, children?: DocumentSymbol[]): DocumentSymbol[] {
        const cst = node.$cstNode;
        if (!cst) return [];
        const nameNode = GrammarUtils.findNodeForProperty(cst, 'name') ?? cst;
        return [{
            name: name || '?',
            kind,
            detail,
            range: cst.range,
            selectionRange: nameNode.range,
            children: children && children.length ? children : undefined
        }];
    }

    private symbolAt(cst: { range: DocumentSymbol['range'] }, name: string, kind: SymbolKind, detail: string): DocumentSymbol[] {
        return [{ name: name || '?', kind, detail, range: cst.range, selectionRange: cst.range }];
    }
}


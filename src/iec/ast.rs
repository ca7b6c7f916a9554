//! The Structured Text AST: POUs with their declarations and statements, configurations with their tasks and program instances, every node with its span.

use crate::diag::Span;

/// A name as written, with where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ident {
    /// As written (IEC names compare case-insensitively).
    pub name: String,
    /// Where.
    pub span: Span,
}

impl Ident {
    /// The name upper-cased: the key names compare by.
    pub fn key(&self) -> String {
        self.name.to_ascii_uppercase()
    }
}

/// A whole file: POUs and configurations.
#[derive(Clone, Debug, Default)]
pub struct Unit {
    /// `PROGRAM`, `FUNCTION_BLOCK` and `FUNCTION` declarations, in order.
    pub pous: Vec<Pou>,
    /// `CONFIGURATION` declarations.
    pub configs: Vec<Config>,
}

/// What a POU is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PouKind {
    /// `PROGRAM`.
    Program,
    /// `FUNCTION_BLOCK`.
    FunctionBlock,
    /// `FUNCTION`.
    Function,
}

/// A program organisation unit.
#[derive(Clone, Debug)]
pub struct Pou {
    /// What it is.
    pub kind: PouKind,
    /// Its name.
    pub name: Ident,
    /// Its variables, in declaration order.
    pub vars: Vec<VarDecl>,
    /// A function's result type.
    pub result: Option<Ident>,
    /// Its statements or instructions.
    pub body: Body,
    /// From the keyword to its end keyword.
    pub span: Span,
}

/// A POU's body: Structured Text statements, Instruction List lines or a sequential
/// function chart.
#[derive(Clone, Debug)]
pub enum Body {
    /// Structured Text.
    St(Vec<Stmt>),
    /// Instruction List.
    Il(Vec<IlLine>),
    /// A sequential function chart (`crate::iec::sfc` turns it into the Structured Text
    /// matiec runs for it before lowering).
    Sfc(Sfc),
}

/// A sequential function chart: its steps, transitions and actions, each in the order
/// written.
#[derive(Clone, Debug, Default)]
pub struct Sfc {
    /// `STEP` and `INITIAL_STEP`.
    pub steps: Vec<Step>,
    /// `TRANSITION … END_TRANSITION`.
    pub transitions: Vec<Transition>,
    /// `ACTION … END_ACTION`.
    pub actions: Vec<Action>,
    /// Variables the chart's generator declares: the results of the functions in its LD
    /// and FBD networks (`_TMP_NOT12_OUT`).
    pub temps: Vec<VarDecl>,
}

/// A step and its action associations.
#[derive(Clone, Debug)]
pub struct Step {
    /// Its name.
    pub name: Ident,
    /// `INITIAL_STEP`.
    pub initial: bool,
    /// `action(qualifier)`, in order.
    pub actions: Vec<Association>,
}

/// An action association `A(N)`, `A(D, T#2s)`, `A()`.
#[derive(Clone, Debug)]
pub struct Association {
    /// The action: an `ACTION`'s name or a BOOL variable.
    pub action: Ident,
    /// Its qualifier as written (`None`: `A()`, which matiec runs unlike `A(N)`).
    pub qualifier: Option<Ident>,
    /// A timed qualifier's duration.
    pub time: Option<Expr>,
    /// The whole association.
    pub span: Span,
}

/// A transition.
#[derive(Clone, Debug)]
pub struct Transition {
    /// `TRANSITION name`.
    pub name: Option<Ident>,
    /// `(PRIORITY := n)`, with where.
    pub priority: Option<(i128, Span)>,
    /// The steps it leaves.
    pub from: Vec<Ident>,
    /// The steps it enters.
    pub to: Vec<Ident>,
    /// `:= condition;`.
    pub condition: Expr,
    /// From `TRANSITION` to `END_TRANSITION`.
    pub span: Span,
}

/// An action with a body.
#[derive(Clone, Debug)]
pub struct Action {
    /// Its name.
    pub name: Ident,
    /// Its statements.
    pub body: Vec<Stmt>,
    /// From `ACTION` to `END_ACTION`.
    pub span: Span,
}

/// One line of an Instruction List body.
#[derive(Clone, Debug)]
pub struct IlLine {
    /// `label:`.
    pub label: Option<Ident>,
    /// The instruction (`None`: a line with only a label).
    pub instr: Option<IlInstr>,
    /// Where.
    pub span: Span,
}

/// When an IL instruction acts: always, or by the current result (`C`, `CN` modifiers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IlCond {
    /// No modifier.
    Always,
    /// `C`: when the current result is TRUE.
    IfTrue,
    /// `CN`: when it is FALSE.
    IfFalse,
}

/// An Instruction List instruction.
#[derive(Clone, Debug)]
pub enum IlInstr {
    /// An operator on the current result: `LD x`, `ANDN y`, `GT 5`, `AND( … )`, `NOT`.
    Op {
        /// The operator.
        op: IlOp,
        /// The `N` modifier (the operand negated).
        negate: bool,
        /// The operand (none for `NOT` and for a `(` with no operand on its line).
        operand: Option<Expr>,
        /// The lines of `OP( … )`: their result is the operand.
        nested: Option<Vec<IlLine>>,
        /// The operator as written.
        word: Ident,
    },
    /// `CAL inst(args)`, `CALC`, `CALCN`.
    Call {
        /// When.
        cond: IlCond,
        /// The instance.
        instance: Expr,
        /// The arguments.
        args: Vec<Arg>,
        /// The operator as written.
        word: Ident,
    },
    /// A function-block input used as an operator: `CLK R1` calls `R1(CLK := current result)`;
    /// also `S`/`R` with an instance operand.
    FbInput {
        /// The input, upper-case (`IN`, `CLK`, `S1`, …).
        pin: String,
        /// The instance.
        instance: Expr,
        /// The operator as written.
        word: Ident,
    },
    /// `JMP label`, `JMPC`, `JMPCN`.
    Jump {
        /// When.
        cond: IlCond,
        /// The target.
        label: Ident,
        /// The operator as written.
        word: Ident,
    },
    /// `RET`, `RETC`, `RETCN`.
    Return {
        /// When.
        cond: IlCond,
        /// The operator as written.
        word: Ident,
    },
    /// A property comment.
    Assert(Expr, Option<Ident>),
}

/// An IL operator on the current result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IlOp {
    /// `LD`: the result is the operand.
    Ld,
    /// `ST`: the operand is set to the result.
    St,
    /// `S`: the operand is set when the result is TRUE.
    S,
    /// `R`: the operand is reset when the result is TRUE.
    R,
    /// `NOT`: the result is negated.
    Not,
    /// A binary operator: `AND` (`&`), `OR`, `XOR`, `ADD`…`MOD`, `GT`…`NE`.
    Bin(BinOp),
    /// A standard or user function as an operator (`MAX b`): the result is its first argument.
    Function(Ident),
}

/// A variable section's class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarClass {
    /// `VAR`.
    Local,
    /// `VAR_INPUT`.
    Input,
    /// `VAR_OUTPUT`.
    Output,
    /// `VAR_IN_OUT`.
    InOut,
    /// `VAR_GLOBAL`.
    Global,
    /// `VAR_EXTERNAL`.
    External,
    /// `VAR_TEMP`.
    Temp,
}

/// One declared variable.
#[derive(Clone, Debug)]
pub struct VarDecl {
    /// Its name.
    pub name: Ident,
    /// Its section.
    pub class: VarClass,
    /// Its type (`BOOL`, `TON`, `INT`, a user type), upper-cased, with where.
    pub ty: Ident,
    /// Its initial value.
    pub init: Option<Expr>,
    /// `RETAIN`.
    pub retain: bool,
    /// `CONSTANT`.
    pub constant: bool,
    /// `AT %IX0.1`.
    pub location: Option<String>,
    /// Made by the front end (a step's bits of a chart), not by the program's author.
    pub made: bool,
    /// The limits of its subrange type (`TYPE R : INT (0..100); END_TYPE`), whose name
    /// `ty` then no longer gives: it is the base type's.
    pub range: Option<(i64, i64)>,
}

/// An expression.
#[derive(Clone, Debug)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub span: Span,
}

/// The expressions.
#[derive(Clone, Debug)]
pub enum ExprKind {
    /// `TRUE`, `FALSE`.
    Bool(bool),
    /// An integer literal.
    Int(i128),
    /// A duration, in µs.
    Time(u64),
    /// Any other literal (real, typed, string, direct address), as written.
    Literal(String),
    /// A variable.
    Var(Ident),
    /// `a.b`.
    Member(Box<Expr>, Ident),
    /// `a[i]`.
    Index(Box<Expr>, Vec<Expr>),
    /// `NOT e`, `-e`.
    Unary(UnOp, Box<Expr>),
    /// `a op b`.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// A function call `F(args)`.
    Call(Ident, Vec<Arg>),
}

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    /// `NOT`.
    Not,
    /// `-`.
    Neg,
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `OR`.
    Or,
    /// `XOR`.
    Xor,
    /// `AND`, `&`.
    And,
    /// `=`.
    Eq,
    /// `<>`.
    Ne,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `MOD`.
    Mod,
    /// `**`.
    Pow,
}

/// A call argument.
#[derive(Clone, Debug)]
pub enum Arg {
    /// `e`.
    Positional(Expr),
    /// `IN := e`.
    Input(Ident, Expr),
    /// `Q => x`, `NOT Q => x`.
    Output(Ident, bool, Expr),
}

/// A statement.
#[derive(Clone, Debug)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where.
    pub span: Span,
}

/// The statements.
#[derive(Clone, Debug)]
pub enum StmtKind {
    /// `target := value`.
    Assign(Expr, Expr),
    /// `instance(args)`.
    Call(Expr, Vec<Arg>),
    /// `IF … ELSIF … ELSE … END_IF`.
    If(Vec<(Expr, Vec<Stmt>)>, Vec<Stmt>),
    /// `CASE selector OF … ELSE … END_CASE` (labels: values or ranges).
    Case(Expr, Vec<CaseArm>, Vec<Stmt>),
    /// `FOR v := a TO b BY c DO … END_FOR`.
    For(Ident, Expr, Expr, Option<Expr>, Vec<Stmt>),
    /// `WHILE c DO … END_WHILE`.
    While(Expr, Vec<Stmt>),
    /// `REPEAT … UNTIL c END_REPEAT`.
    Repeat(Vec<Stmt>, Expr),
    /// `EXIT`.
    Exit,
    /// `CONTINUE`.
    Continue,
    /// `RETURN`.
    Return,
    /// `;`.
    Empty,
    /// A property comment `//#ASSERT expr : name`.
    Assert(Expr, Option<Ident>),
}

/// A `CASE` arm: its labels (a value, or a range `a..b`) and its statements.
pub type CaseArm = (Vec<(Expr, Option<Expr>)>, Vec<Stmt>);

/// A configuration.
#[derive(Clone, Debug)]
pub struct Config {
    /// Its name.
    pub name: Ident,
    /// Its tasks, over all its resources.
    pub tasks: Vec<Task>,
    /// Its program instances, in declaration order.
    pub instances: Vec<Instance>,
    /// Its global variables.
    pub globals: Vec<VarDecl>,
}

/// A task.
#[derive(Clone, Debug)]
pub struct Task {
    /// Its name.
    pub name: Ident,
    /// `INTERVAL`, in µs.
    pub interval: Option<u64>,
    /// `SINGLE`: an event task.
    pub single: bool,
    /// `PRIORITY`.
    pub priority: i128,
}

/// A program instance: `PROGRAM inst WITH task : Type;`.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Its name.
    pub name: Ident,
    /// Its task.
    pub task: Option<Ident>,
    /// The program type.
    pub ty: Ident,
}

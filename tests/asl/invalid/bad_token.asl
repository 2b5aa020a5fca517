// expect: 3:10 unexpected character `#`
// `#` is not an AgentSpeak token.
cupboard(#top).

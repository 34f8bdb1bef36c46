#version 450
{{extensions}}
// {{stamp}}

{{declarations}}
layout(location = 0) out vec4 out_color;

{{prelude}}
void main() {
    {{body}}

    out_color = {{result}};
}

// {{stamp}}

{{declarations}}

{{prelude}}
float4 main({{inputs}}) : SV_Target0 {
    {{body}}

    return {{result}};
}

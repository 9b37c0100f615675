#include "core/common/issue.h"

namespace terra {

std::string formatIssues(const std::vector<Issue>& issues) {
    std::string text;
    for (const Issue& issue : issues) {
        if (!text.empty()) text += '\n';
        text += issue.where.empty() ? issue.message : issue.where + ": " + issue.message;
    }
    return text;
}

}  // namespace terra
